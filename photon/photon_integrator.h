#pragma once
// The photon-mapping integrator (the paper's §4 after Jensen 1996), `--integrator photon`.
//
// Camera paths are the Whitted integrator's own (tracer/whitted.h: direct light through shadow
// rays, mirror reflection, Fresnel refraction), with a shading policy that adds, at every diffuse
// surface, the light the photon maps hold:
//   L = direct (shadow rays) + albedo/pi * (E_caustic + E_indirect), where
//   - E_caustic is the caustic map's flux density there (light after specular bounces only);
//   - E_indirect is the global map's flux density there (final_gather_rays = 0), or with final
//     gathering pi/N times the sum of the radiance N cosine-distributed rays bring back, where
//     each gather ray's diffuse hit is shaded as direct + albedo/pi * (E_caustic + E_global) and
//     a gather ray that escapes brings nothing (the background lights no surface here: photons
//     come from the point lights only).
// The global map leaves out each path's first diffuse hit (direct light, or a caustic: both
// computed otherwise), so no light is counted twice. Rays that escape from the camera path see
// the background, as in Whitted.

#include "emission.h"
#include "map_needs.h"
#include "photon_map.h"
#include "photon_params.h"
#include "photon_tracing.h"

#include "tracer/render.h"

#include <nlohmann/json.hpp>

namespace photon {

/// The row of the integrator table.
const tracer::Integrator& photon_integrator();

/// The photon maps of one render, traced and built.
struct PhotonMaps {
  MapNeeds needs;            ///< Which maps the scene can use.
  PassResult global_pass;    ///< The global pass (photons kept only when asked for).
  PassResult caustic_pass;   ///< The caustic pass.
  PhotonMap global;          ///< Empty when not needed or nothing was stored.
  PhotonMap caustic;         ///< Empty when not needed or nothing was stored.
  double global_build_ms = 0.0;   ///< Tree build wall time, milliseconds.
  double caustic_build_ms = 0.0;  ///< Tree build wall time, milliseconds.
  float max_radius = 0.0f;   ///< The gather radius in use, world units (+inf: unbounded).
};

/// Traces and builds the maps `params` asks for over `scene` through `accel`, on `options.threads`
/// threads, within options.limits (throws knobs::ConfigError naming the photon count that does
/// not fit). With `keep_photons` the passes keep their photon arrays (tests compare them).
PhotonMaps make_photon_maps(const tracer::Scene& scene, const accel::AnyAccel& accel,
                            const PhotonParams& params, const tracer::RenderOptions& options,
                            bool keep_photons = false);

/// The gather radius `params` resolves to on `scene`: max_radius, or for "auto" 1/20 of the
/// diagonal of the box around the bounded primitives (+inf when there are none).
float resolve_max_radius(const tracer::Scene& scene, const PhotonParams& params);

}  // namespace photon
