#include "photon_tracing.h"

#include "photon_tracer.h"

#include "tracer/intersector.h"
#include "tracer/parallel.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <type_traits>

namespace photon {

namespace {

/// Photon paths per work item of a round.
constexpr std::uint64_t kChunkPaths = 1024;
/// Paths in a pass's first round, at most: enough to learn how many stores a path makes.
constexpr std::uint64_t kFirstRound = 65536;
/// Paths in one round, at most (path indices within a round are 32-bit).
constexpr std::uint64_t kMaxRound = std::uint64_t(1) << 30;

}  // namespace

PassResult trace_photon_pass(const tracer::Scene& scene, const accel::AnyAccel& accel,
                             const PassOptions& o) {
  PassResult result;
  const Emission emission(scene, o.pass, o.uniform_fallback);
  if (emission.empty() || o.target == 0) return result;
  const auto start = std::chrono::steady_clock::now();
  const int threads = tracer::resolve_threads(o.threads);
  const std::uint64_t cap = o.max_emitted ? o.max_emitted : 256 * o.target + 65536;

  LightSequence sequence = emission.sequence();
  std::vector<TracedPhoton> stored;
  std::vector<std::uint32_t> lights;
  std::vector<PathCounters> counters(static_cast<std::size_t>(threads));
  std::vector<accel::TraversalCounters> traversal(static_cast<std::size_t>(threads));
  std::uint64_t next = 0;        // index of the next path to trace
  std::uint64_t stores_made = 0; // stores of every traced path, dropped ones included
  bool done = false;

  tracer::with_intersector(scene.geometry, accel, o.count_traversal, o.triangle_test, [&](const auto& base) {
    using Isect = std::decay_t<decltype(base)>;
    while (!done) {
      if (next >= cap) {
        result.stopped = "stopped after " + std::to_string(cap) + " photon paths (the pass's cap)";
        break;
      }
      // Round size: the first is small; later ones aim at the photons still missing, from the
      // stores per path seen so far (at least 1/256), with 5% to spare.
      std::uint64_t round = std::min<std::uint64_t>(o.target, kFirstRound);
      if (next > 0) {
        const double per_path = std::max(double(stores_made) / double(next), 1.0 / 256.0);
        round = std::uint64_t(std::ceil(double(o.target - stored.size()) / per_path * 1.05)) + 256;
      }
      round = std::min({round, cap - next, kMaxRound});

      const LightSequence before = sequence;
      lights.resize(round);
      for (std::uint64_t i = 0; i < round; ++i) lights[i] = sequence.next();

      const std::uint64_t chunks = (round + kChunkPaths - 1) / kChunkPaths;
      std::vector<std::vector<TracedPhoton>> out(chunks);
      tracer::parallel_items(threads, int(chunks), [&](int worker, int chunk) {
        const Isect isect = Isect::kCounting
                                ? base.with_counters(&traversal[std::size_t(worker)])
                                : base;
        const PhotonPathTracer<Isect> tracer(scene, isect, o.pass, o.max_depth);
        PathCounters& c = counters[std::size_t(worker)];
        const std::uint64_t end = std::min(round, std::uint64_t(chunk + 1) * kChunkPaths);
        for (std::uint64_t p = std::uint64_t(chunk) * kChunkPaths; p < end; ++p) {
          PhotonRng rng(o.seed, std::uint64_t(o.pass), next + p);
          const float u1 = rng.uniform(), u2 = rng.uniform();
          tracer.trace(emission.emit(lights[p], u1, u2), rng, lights[p], std::uint32_t(p),
                       out[std::size_t(chunk)], c);
        }
      });

      // Join in path order; stop at the path that completes the map.
      for (const auto& chunk : out) {
        stores_made += chunk.size();
        for (const TracedPhoton& t : chunk) {
          if (done) break;
          stored.push_back(t);
          if (stored.size() == o.target) {
            done = true;
            result.emitted = next + t.path + 1;
            std::vector<std::uint64_t> n = before.counts();
            for (std::uint32_t p = 0; p <= t.path; ++p) ++n[lights[p]];
            result.emitted_per_light = std::move(n);
          }
        }
      }
      next += round;
      if (done) break;
      std::uint64_t diffuse_hits = 0;
      for (const PathCounters& c : counters) diffuse_hits += c.diffuse_hits;
      if (diffuse_hits == 0) {
        result.stopped = "no photon of the first " + std::to_string(next) +
                         " reached a surface with a diffuse part";
        break;
      }
    }
  });
  if (!done) {
    result.emitted = next;
    result.emitted_per_light = sequence.counts();
  }

  // Each light's photons share its power over the paths it emitted.
  std::vector<Color> power(emission.lights().size());
  for (std::uint32_t l = 0; l < power.size(); ++l)
    power[l] = emission.photon_power(l, result.emitted_per_light[l]);
  result.photons.reserve(stored.size());
  for (const TracedPhoton& t : stored)
    result.photons.push_back(Photon::make(t.position, t.weight * power[t.light], t.direction));

  for (const PathCounters& c : counters) {
    result.rays += c.rays;
    result.diffuse_hits += c.diffuse_hits;
  }
  for (const accel::TraversalCounters& t : traversal) result.traversal += t;
  result.trace_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

void to_json(nlohmann::json& j, const PassResult& r) {
  j = {{"emitted", r.emitted},
       {"emitted_per_light", r.emitted_per_light},
       {"photon_rays", r.rays},
       {"diffuse_hits", r.diffuse_hits},
       {"trace_ms", r.trace_ms}};
  if (!r.stopped.empty()) j["stopped"] = r.stopped;
}

}  // namespace photon
