#pragma once
// Progressive photon mapping (Hachisuka, Ogaki and Jensen 2008), `--integrator ppm`: the
// consistent estimator that makes the reference for the photon-mapping integrator's knobs
// (docs/accuracy.md). It converges to the radiance the photon integrator estimates, with no
// knob of the photon integrator's own.
//
// Camera paths are the Whitted integrator's (tracer/whitted.h), as in the photon integrator:
// direct light through shadow rays, mirror reflection and Fresnel refraction are exact. Every
// diffuse surface a camera path meets becomes a visible point with a radius R, an accumulated
// photon count N and accumulated flux tau. Then `passes` photon passes each trace
// `photons_per_pass` photons into a fresh caustic and global map (photon/photon_tracing.h; the
// two together hold all light after at least one bounce, the part the photon maps estimate) and
// every visible point gathers the M photons within R (photon/photon_map.h) and updates
//   N' = N + alpha M,   R'^2 = R^2 (N + alpha M) / (N + M),   tau' = (tau + Phi_M) R'^2 / R^2
// with alpha = 2/3 (pbrt-v3's SPPM), so R shrinks and the estimate tau / (pi R^2 passes) of the
// flux density becomes consistent: its variance and its bias both vanish as passes grow, and its
// mean squared error falls as N^-2/3 (Knaus and Zwicker 2011; Kaplanyan and Dachsbacher 2013).

#include "tracer/render.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>

namespace photon {

struct PpmParams {
  /// Photon passes, each with fresh maps.
  int passes = 64;
  /// Photons stored per map (caustic and global) per pass, photons.
  int photons_per_pass = 100000;
  /// Photon paths one map may emit in a pass before it stops short of photons_per_pass, paths,
  /// 0 = the tracer's own cap (256 per photon asked for, plus 65536). A map cut
  /// short keeps its photons at the light's power over the paths emitted, so its estimate stays
  /// unbiased; what it bounds is the time a pass spends on light that rarely reaches a diffuse
  /// surface (the ring's global map: about 260 paths per photon stored).
  std::uint64_t max_paths = 0;
  /// Radius every visible point starts with, world units; unset ("auto"): each point's
  /// distance to the initial_photons-th nearest photon of a pilot pass (photons not counted in
  /// the estimate), at most 1/20 of the diagonal of the box around the scene's bounded primitives.
  std::optional<float> initial_radius;
  /// Photons of the pilot pass within an automatic initial radius.
  int initial_photons = 32;
  /// The share of new photons kept in N at each pass, in (0, 1]: 2/3 balances the bias and the
  /// variance that the shrinking radius leaves (pbrt-v3's default).
  float alpha = 2.0f / 3.0f;
  /// Surface interactions per photon path before it is dropped.
  int max_photon_depth = 64;
  /// Seed of the photon paths; pass i draws from a seed of its own derived from it.
  std::uint64_t seed = 1;
  /// Ray/triangle routine of camera, shadow and photon rays.
  tracer::TriangleTest triangle = tracer::TriangleTest::Watertight;

  /// The table (initial_radius as "auto" or its number; one-line errors such as "ppm: parameter
  /// 'passes' must be in [1, 1000000], got 0").
  static const knobs::KnobTable<PpmParams>& knobs();
};

/// The row of the integrator table.
const tracer::Integrator& ppm_integrator();

}  // namespace photon
