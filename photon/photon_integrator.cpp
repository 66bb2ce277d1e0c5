#include "photon_integrator.h"

#include "cycle_clock.h"
#include "photon_rng.h"
#include "photon_tracer.h"

#include "tracer/render_frame.h"
#include "tracer/whitted.h"

#include "accel/accel.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <mutex>
#include <numbers>
#include <string>
#include <type_traits>

namespace photon {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// Random-number stream of the final gather (photon passes use 0 and 1).
constexpr std::uint64_t kGatherStream = 2;

/// One worker's share of the shading work.
struct ShadingTally {
  GatherCounters counters;        ///< kNN work (counting pass only).
  std::uint64_t lookups = 0;      ///< Map lookups.
  std::uint64_t gather_ticks = 0; ///< Cycle-clock ticks inside lookups and density estimates.
  std::uint64_t direct_ticks = 0; ///< Cycle-clock ticks inside direct light (shadow rays).
};

/// What every worker's shading shares: the maps and the knobs.
struct ShadingSetup {
  const PhotonMaps* maps;
  GatherParams gather;
  DensityParams density;
  int final_gather_rays;
  std::uint64_t seed;
};

/// The photon integrator's shading policy for tracer::Whitted (see photon_integrator.h).
template <bool Count>
class PhotonShading {
 public:
  PhotonShading(const ShadingSetup& setup, ShadingTally* tally) : setup_(&setup), tally_(tally) {}

  template <class Tracer>
  tracer::Color diffuse(const Tracer& t, const tracer::DiffuseHit& h, const tracer::PathState& path,
                        tracer::RayCounts& counts) const {
    const std::uint64_t d0 = cycle_ticks();
    tracer::Color radiance = t.direct(h.sp, h.n, h.n_geo, h.to_eye, h.response, counts);
    tally_->direct_ticks += cycle_ticks() - d0;
    const tracer::Color brdf = h.response.albedo * (1.0f / std::numbers::pi_v<float>);
    if (!(std::max(brdf.x, std::max(brdf.y, brdf.z)) > 0.0f)) return radiance;
    const PhotonMaps& maps = *setup_->maps;
    tracer::Color flux(0.0f);
    if (!maps.caustic.empty()) flux += estimate(maps.caustic, h.sp.p, h.n);
    if (!maps.global.empty()) {
      if (path.gathers == 0 && setup_->final_gather_rays > 0)
        flux += final_gather(t, h, path, counts);
      else
        flux += estimate(maps.global, h.sp.p, h.n);
    }
    return radiance + brdf * flux;
  }

  tracer::Color escaped(const tracer::Scene& scene, const tracer::PathState& path) const {
    return path.gathers == 0 ? scene.background : tracer::Color(0.0f);
  }

 private:
  /// Flux density (W/m^2) of `map` at p on the side n faces.
  tracer::Color estimate(const PhotonMap& map, const tracer::Vec3& p, const tracer::Vec3& n) const {
    const std::uint64_t g0 = cycle_ticks();
    tally_->lookups++;
    map.gather<Count>(p, n, setup_->gather, found_, &tally_->counters);
    const tracer::Color e = flux_density(map, found_, setup_->density, n);
    tally_->gather_ticks += cycle_ticks() - g0;
    return e;
  }

  /// Irradiance at h from N stratified cosine-distributed gather rays: pi/N times their radiance.
  template <class Tracer>
  tracer::Color final_gather(const Tracer& t, const tracer::DiffuseHit& h,
                             const tracer::PathState& path, tracer::RayCounts& counts) const {
    const int n_rays = setup_->final_gather_rays;
    const int m = int(std::ceil(std::sqrt(double(n_rays))));  // strata per row
    const int rows = (n_rays + m - 1) / m;
    // The gather's random numbers depend on the hit alone (its position and normal bits).
    std::uint64_t key = 0;
    for (int a = 0; a < 3; ++a)
      key = PhotonRng::mix(key ^ std::bit_cast<std::uint32_t>(h.sp.p[a]) ^
                           (std::uint64_t(std::bit_cast<std::uint32_t>(h.n[a])) << 32));
    PhotonRng rng(setup_->seed, kGatherStream, key);
    const tracer::Color weight = path.throughput * h.response.albedo;
    tracer::Color sum(0.0f);
    for (int i = 0; i < n_rays; ++i) {
      const float u1 = (float(i % m) + rng.uniform()) / float(m);
      const float u2 = (float(i / m) + rng.uniform()) / float(rows);
      const tracer::Vec3 dir =
          cosine_direction(h.n, std::min(u1, 0x1.fffffep-1f), std::min(u2, 0x1.fffffep-1f));
      if (!(glm::dot(dir, h.n_geo) > 0.0f)) continue;
      sum += t.spawn(h.sp, h.n_geo, dir, path.depth, weight, path.absorption, counts.gather, counts,
                     path.gathers + 1);
    }
    return sum * (std::numbers::pi_v<float> / float(n_rays));
  }

  const ShadingSetup* setup_;
  ShadingTally* tally_;
  mutable Neighbors found_;  ///< Reused by every lookup of this worker.
};

/// The scene's bounded primitives' box diagonal / 20, or +inf.
float auto_radius(const tracer::Scene& scene) {
  accel::Aabb box;
  for (const accel::Aabb& b : scene.geometry.primitive_bounds()) box.grow(b);
  if (box.is_empty()) return std::numeric_limits<float>::infinity();
  const float diagonal = glm::length(box.hi - box.lo);
  return diagonal > 0.0f ? diagonal / 20.0f : std::numeric_limits<float>::infinity();
}

/// Bytes a map of `photons` needs while it is traced and built: the tracer's record, the photon
/// array, the tree's copy and its index.
std::uint64_t map_bytes(std::uint64_t photons) {
  return photons * (sizeof(TracedPhoton) + 2 * sizeof(Photon) + sizeof(std::uint32_t));
}

void check_budget(const PhotonParams& p, const MapNeeds& needs, const accel::BuildLimits& limits) {
  const std::uint64_t budget = accel::memory_budget_bytes(limits);
  const std::uint64_t global = needs.global ? map_bytes(std::uint64_t(p.global_photons)) : 0;
  const std::uint64_t caustic = needs.caustic ? map_bytes(std::uint64_t(p.caustic_photons)) : 0;
  if (global + caustic <= budget) return;
  const char* knob = global >= caustic ? "global_photons" : "caustic_photons";
  const int count = global >= caustic ? p.global_photons : p.caustic_photons;
  char msg[256];
  std::snprintf(msg, sizeof msg,
                "photon: knob '%s' = %d needs %.1f MiB of photon maps (%.1f MiB in all), "
                "more than the memory budget of %.1f MiB (--max-memory)",
                knob, count, double(std::max(global, caustic)) / 1048576.0,
                double(global + caustic) / 1048576.0, double(budget) / 1048576.0);
  throw knobs::ConfigError(msg);
}

nlohmann::json map_json(const PassResult& pass, const PhotonMap& map, double build_ms,
                        bool needed, const std::string& reason) {
  if (!needed) return {{"skipped", reason}};
  nlohmann::json j = pass;
  j["stored"] = map.size();
  j["build_ms"] = build_ms;
  j["tree"] = {{"nodes", map.stats().nodes},
               {"leaves", map.stats().leaves},
               {"depth", map.stats().depth},
               {"memory_bytes", map.stats().memory_bytes}};
  return j;
}

std::string photon_summary(const nlohmann::json& stats) {
  std::string out;
  char line[320];
  for (const char* kind : {"global", "caustic"}) {
    const nlohmann::json& m = stats.at("maps").at(kind);
    if (m.contains("skipped")) {
      std::snprintf(line, sizeof line, "photons  %s map skipped: %s\n", kind,
                    m["skipped"].get<std::string>().c_str());
    } else {
      std::snprintf(line, sizeof line,
                    "photons  %s map: %llu stored from %llu emitted paths, traced in %.3f ms, "
                    "built in %.3f ms%s%s\n",
                    kind, m["stored"].get<unsigned long long>(),
                    m["emitted"].get<unsigned long long>(), m["trace_ms"].get<double>(),
                    m["build_ms"].get<double>(), m.contains("stopped") ? "; " : "",
                    m.value("stopped", std::string()).c_str());
    }
    out += line;
  }
  const nlohmann::json& t = stats.at("timings");
  std::snprintf(line, sizeof line,
                "gather   %llu lookups; thread time in gathers %.3f ms, in direct light %.3f ms, "
                "render loop %.3f ms wall\n",
                stats.at("gather").at("lookups").get<unsigned long long>(),
                t["gather_thread_ms"].get<double>(), t["direct_thread_ms"].get<double>(),
                t["render_loop_ms"].get<double>());
  return out + line;
}

void photon_check(const tracer::Scene& scene, const tracer::RenderOptions& options,
                  const nlohmann::json& knobs) {
  const PhotonParams params = knobs.get<PhotonParams>();
  MapNeeds needs = map_needs(scene);
  if (!params.skip_unneeded_maps) needs.global = needs.caustic = true;
  check_budget(params, needs, options.limits);
}

const knobs::AnyKnobTable& photon_knobs() { return PhotonParams::knobs(); }

tracer::RenderResult render_photon(const tracer::Scene& scene, const accel::AnyAccel& accel,
                                   const tracer::RenderOptions& given,
                                   const nlohmann::json& knobs) {
  const auto start = Clock::now();
  const PhotonParams params = knobs.get<PhotonParams>();
  tracer::RenderOptions options = given;
  options.triangle_test = params.triangle;
  const PhotonMaps maps = make_photon_maps(scene, accel, params, options);
  const double prepare_ms = ms_since(start);

  const ShadingSetup setup{&maps, params.gather(maps.max_radius), params.density(),
                           params.final_gather_rays, params.seed};
  std::deque<ShadingTally> tallies;  // one per worker; deque: pointers stay valid
  std::mutex tallies_mutex;
  const TickRate rate;
  tracer::RenderResult result = tracer::render_frame(
      scene, accel, options, tracer::FilmSampling::PixelSamples, [&](const auto& isect) {
        using Isect = std::decay_t<decltype(isect)>;
        ShadingTally* tally;
        {
          std::lock_guard<std::mutex> lock(tallies_mutex);
          tally = &tallies.emplace_back();
        }
        return tracer::Whitted<Isect, PhotonShading<Isect::kCounting>>(
            scene, isect, scene.render, PhotonShading<Isect::kCounting>(setup, tally));
      });
  const double ms_per_tick = rate.ms_per_tick();
  const double loop_ms = result.render_ms;
  result.render_ms += prepare_ms;

  // Photon rays count as rays of the render; the structure's work on them as its traversal.
  result.rays.photon = maps.global_pass.rays + maps.caustic_pass.rays;
  result.traversal += maps.global_pass.traversal;
  result.traversal += maps.caustic_pass.traversal;

  ShadingTally sum;
  for (const ShadingTally& t : tallies) {
    sum.counters += t.counters;
    sum.lookups += t.lookups;
    sum.gather_ticks += t.gather_ticks;
    sum.direct_ticks += t.direct_ticks;
  }
  nlohmann::json gather = {{"lookups", sum.lookups},
                           {"gather_ms", double(sum.gather_ticks) * ms_per_tick}};
  if (options.count_traversal) {
    gather["counters"] = sum.counters;
    gather["photons_visited_per_lookup"] =
        sum.lookups ? double(sum.counters.nodes_visited) / double(sum.lookups) : 0.0;
    gather["photons_tested_per_lookup"] =
        sum.lookups ? double(sum.counters.photons_tested) / double(sum.lookups) : 0.0;
  }
  result.stats = {
      {"params", params},
      {"max_radius", maps.max_radius},
      {"maps",
       {{"global", map_json(maps.global_pass, maps.global, maps.global_build_ms, maps.needs.global,
                            maps.needs.global_reason)},
        {"caustic", map_json(maps.caustic_pass, maps.caustic, maps.caustic_build_ms,
                             maps.needs.caustic, maps.needs.caustic_reason)}}},
      {"gather", gather},
      {"timings",
       {{"photon_trace_ms", maps.global_pass.trace_ms + maps.caustic_pass.trace_ms},
        {"map_build_ms", maps.global_build_ms + maps.caustic_build_ms},
        {"render_loop_ms", loop_ms},
        {"gather_thread_ms", double(sum.gather_ticks) * ms_per_tick},
        {"direct_thread_ms", double(sum.direct_ticks) * ms_per_tick}}}};
  return result;
}

}  // namespace

float resolve_max_radius(const tracer::Scene& scene, const PhotonParams& params) {
  return params.max_radius ? *params.max_radius : auto_radius(scene);
}

PhotonMaps make_photon_maps(const tracer::Scene& scene, const accel::AnyAccel& accel,
                            const PhotonParams& params, const tracer::RenderOptions& options,
                            bool keep_photons) {
  PhotonMaps maps;
  maps.needs = map_needs(scene);
  if (!params.skip_unneeded_maps) {
    maps.needs.global = maps.needs.caustic = true;
    maps.needs.global_reason.clear();
    maps.needs.caustic_reason.clear();
  }
  check_budget(params, maps.needs, options.limits);
  maps.max_radius = resolve_max_radius(scene, params);

  PassOptions po;
  po.max_depth = params.max_photon_depth;
  po.seed = params.seed;
  po.threads = options.threads;
  po.count_traversal = options.count_traversal;
  po.triangle_test = options.triangle_test;
  po.uniform_fallback = !params.skip_unneeded_maps;
  const auto run = [&](PhotonPass pass, int target, PassResult& out, PhotonMap& map,
                       double& build_ms) {
    po.pass = pass;
    po.target = std::uint64_t(target);
    out = trace_photon_pass(scene, accel, po);
    const auto t0 = Clock::now();
    map = PhotonMap(std::span<const Photon>(out.photons), params.tree(), options.limits);
    build_ms = ms_since(t0);
    if (!keep_photons) std::vector<Photon>().swap(out.photons);
  };
  if (maps.needs.global)
    run(PhotonPass::Global, params.global_photons, maps.global_pass, maps.global,
        maps.global_build_ms);
  if (maps.needs.caustic)
    run(PhotonPass::Caustic, params.caustic_photons, maps.caustic_pass, maps.caustic,
        maps.caustic_build_ms);
  return maps;
}

const tracer::Integrator& photon_integrator() {
  static constexpr tracer::Integrator kPhoton{
      "photon",
      "photon mapping (the paper's §4): Whitted camera paths, caustics from a caustic map, "
      "indirect light from a global map (read directly, or by final gathering)",
      photon_knobs, render_photon, photon_summary, photon_check};
  return kPhoton;
}

}  // namespace photon
