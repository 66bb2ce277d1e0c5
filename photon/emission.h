#pragma once
// Where photons come from (the paper's §4: "each light emits photons in proportion to its share
// of the total power"). Photon i of a pass takes its light from a deterministic apportionment
// sequence: after any number N of photons, light j has emitted n_j photons with
// |n_j - N P_j / P| < 2 (P_j its power, P the total), and each of its photons carries
// Phi_j / n_j, so the photons' powers sum to the lights' total exactly and are equal up to the
// rounding of n_j. The direction comes from the photon's own random numbers.
//
// The global pass emits into every direction. The caustic pass emits only into the cone around
// the bounding sphere of the scene's specular primitives (Jensen's projection maps, reduced to
// one cone per light); its photons carry the power that goes into that cone, so the caustic
// map holds the same light it would have with uniform emission, with far fewer photons wasted.

#include "map_needs.h"
#include "vec.h"

#include "tracer/orthonormal_basis.h"
#include "tracer/scene.h"

#include <cstdint>
#include <vector>

namespace photon {

/// The photon passes, each with its own map.
enum class PhotonPass : std::uint8_t {
  Global,   ///< Every direction; stores diffuse hits after the first diffuse bounce.
  Caustic,  ///< Towards the specular primitives; stores the first diffuse hit after them.
};

/// Watts a light shares photons out by: its power times the mean of its colour.
double light_share_power(const tracer::PointLight& light);

/// The apportionment sequence: which light each successive photon comes from.
class LightSequence {
 public:
  LightSequence() = default;
  /// Over lights of the given powers (>= 0, not all 0).
  explicit LightSequence(std::vector<double> powers);

  /// The light of the next photon: the one furthest behind its share (ties: the lower index).
  std::uint32_t next();
  /// Photons given to each light so far.
  const std::vector<std::uint64_t>& counts() const { return counts_; }
  /// Photons given out so far.
  std::uint64_t emitted() const { return emitted_; }

 private:
  std::vector<double> share_;          ///< P_j / P.
  std::vector<std::uint64_t> counts_;  ///< n_j.
  std::uint64_t emitted_ = 0;
};

/// One light of a pass and the cone it emits its photons into.
struct EmittingLight {
  Vec3 position{0.0f};       ///< World units.
  Color power{0.0f};         ///< Watts per channel emitted into the cone.
  Vec3 axis{0.0f, 0.0f, 1.0f};  ///< Unit axis of the cone.
  float cos_max = -1.0f;     ///< Cosine of the cone's half-angle; -1 = every direction.
};

/// The emission of one pass over a scene.
class Emission {
 public:
  /// The emission of `pass`. A caustic pass in a scene without specular primitives has nothing
  /// to aim at and emits nothing, unless `uniform_fallback`: then it emits into every direction
  /// (what a tracer that does not model the scene's needs would do; for measuring that).
  Emission(const tracer::Scene& scene, PhotonPass pass, bool uniform_fallback = false);

  /// True when no light emits into the pass.
  bool empty() const { return lights_.empty(); }
  /// The emitting lights (only those with power in the pass).
  const std::vector<EmittingLight>& lights() const { return lights_; }
  /// A fresh apportionment sequence over lights().
  LightSequence sequence() const;
  /// The ray of a photon from light `l` (index into lights()), direction from two uniforms in
  /// [0, 1): uniform over the light's cone.
  accel::Ray emit(std::uint32_t l, float u1, float u2) const;
  /// Power of each photon of light `l` when `n` photons came from it, watts per channel.
  Color photon_power(std::uint32_t l, std::uint64_t n) const;

 private:
  std::vector<EmittingLight> lights_;
};

using tracer::orthonormal_basis;

}  // namespace photon
