#pragma once
// Tracing one photon pass to the number of photons its map asks for, on every worker thread,
// through any acceleration structure, bit-identically at any thread count.
//
// Paths are traced in rounds of consecutive indices; path i draws from PhotonRng(seed, pass, i)
// and takes its light from the apportionment sequence (emission.h), so what it stores depends on
// i alone. Rounds are cut into chunks of paths, each chunk's stores kept in path order and the
// chunks joined in order, so the stores come out in path order whatever thread traced them. The
// pass stops at the first path whose stores bring the count to the target (its later stores, at
// most a few photons of that one path, are dropped, so the map holds exactly the target);
// `emitted` is that path's index + 1, and each light's photons carry its power over the paths it
// emitted up to there. A pass also stops when `max_emitted` paths are spent, or when its first
// round met no diffuse surface at all (light cannot reach one); the map then holds what was
// stored, at the same power per photon, which keeps its estimate unbiased.

#include "emission.h"
#include "photon.h"

#include "tracer/ray_counts.h"
#include "tracer/scene.h"

#include "accel/accel.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace photon {

struct PassOptions {
  PhotonPass pass = PhotonPass::Global;  ///< Which map.
  std::uint64_t target = 0;              ///< Photons to store, >= 1.
  int max_depth = 64;                    ///< Surface interactions per path.
  std::uint64_t seed = 1;                ///< Seed of every path's random numbers.
  int threads = 0;                       ///< Worker threads; 0 = every hardware thread.
  bool count_traversal = false;          ///< Gather the structure's TraversalCounters.
  tracer::TriangleTest triangle_test = tracer::TriangleTest::Watertight;  ///< Ray/triangle routine.
  /// Paths at most; 0 = 256 per photon asked for, plus 65536.
  std::uint64_t max_emitted = 0;
  /// A caustic pass with no specular primitive to aim at emits into every direction instead of
  /// not at all (Emission's uniform_fallback; skip_unneeded_maps = false).
  bool uniform_fallback = false;
};

/// A traced pass: the photons of its map, and what it took.
struct PassResult {
  std::vector<Photon> photons;          ///< In path order; powers in watts per channel.
  std::uint64_t emitted = 0;            ///< Photon paths emitted (their powers sum to the lights').
  std::vector<std::uint64_t> emitted_per_light;  ///< Paths per emitting light (Emission::lights()).
  std::uint64_t rays = 0;               ///< Photon rays traced.
  std::uint64_t diffuse_hits = 0;       ///< Path hits on surfaces with a diffuse part.
  accel::TraversalCounters traversal;   ///< The structure's work; zero unless counted.
  double trace_ms = 0.0;                ///< Wall time, milliseconds.
  std::string stopped;                  ///< Why it holds fewer photons than asked; "" when full.
};

/// Traces the pass over `scene` through `accel` (built over scene.geometry.primitive_bounds()).
/// An emission with no light, or nothing to aim at, returns an empty result at once.
PassResult trace_photon_pass(const tracer::Scene& scene, const accel::AnyAccel& accel,
                             const PassOptions& options);

/// The pass's statistics (not its photons): paths emitted, rays, diffuse hits, trace time, and
/// why it stopped short.
void to_json(nlohmann::json& j, const PassResult& r);

}  // namespace photon
