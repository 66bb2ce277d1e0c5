#pragma once
// Density estimation from the photons one gather found (the paper's radiance estimate, before
// the BRDF): the flux density sum_p Phi_p w(d_p) / (c pi r^2) in watts per square metre, with
//   box       w = 1,                        c = 1;
//   cone      w = 1 - d / (k_cone r),       c = 1 - 2 / (3 k_cone)   (Jensen; k_cone >= 1);
//   biweight  w = 3 (1 - d^2 / r^2)^2,      c = 1                    (the smooth kernel of pbrt
//             and Mitsuba, 3/pi (1 - d^2/r^2)^2, which integrates to 1 over the unit disc).
// The radius r is the distance of the k-th photon when k were found. With fewer than k found
// within max_radius, or when all k coincide with the query (r = 0), the search disc of radius
// max_radius is the area (its photons are all there is); with an unbounded search that finds
// fewer than k, the farthest photon found; with nothing to measure (empty map, no photon found,
// or r = 0 with an unbounded search) the estimate is 0.
//
// Known bias on a plane of uniform photon density (docs/photon-kdtree.md derives it; tests/
// photon_density_test.cpp checks it by Monte Carlo): with n photons gathered, the box estimate
// averages n/(n-1) of the truth, the cone 1 + 3(k_cone - 1)/((n - 1)(3 k_cone - 2)), and the
// biweight exactly the truth.

#include "knn.h"
#include "photon_map.h"

#include "knobs/knob_table.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace photon {

/// The density-estimation kernels.
enum class DensityFilter : std::uint8_t {
  Box,       ///< Every photon counts fully.
  Cone,      ///< The paper's cone filter, sharper for smaller cone_k.
  Biweight,  ///< The smooth kernel 3/pi (1 - d^2/r^2)^2.
};

/// Knobs of the density estimate.
struct DensityParams {
  /// Kernel (JSON: "box", "cone", "biweight").
  DensityFilter filter = DensityFilter::Cone;
  /// Cone filter constant k (the paper: 1 is the sharpest cone that reaches 0 at r).
  float cone_k = 1.1f;

  static const knobs::KnobTable<DensityParams>& knobs();
};

std::string_view name_of(DensityFilter f);
/// The kernels as knob choices (spelling, value), in display order.
std::vector<std::pair<std::string, DensityFilter>> density_filter_choices();
/// Throws knobs::ConfigError naming the first knob out of range ("density: cone_k ...").
void validate(const DensityParams& p);

/// The squared radius of the disc an estimate divides by (see above), world units squared; 0
/// when there is nothing to measure.
float estimate_radius2(const Neighbors& found);

/// Flux density (watts per square metre per channel) from the photons `found` in `map`.
/// Photons arriving from behind `normal` (dot(direction, normal) >= 0) are left out; a zero
/// normal leaves none out. The photons are summed in order of (distance, original index), so
/// every tree variant gives the same bits. Reorders `found`. Throws knobs::ConfigError for a
/// bad knob.
Color flux_density(const PhotonMap& map, Neighbors& found, const DensityParams& params,
                   const Vec3& normal);

}  // namespace photon
