// Google Benchmark: photon tracing and whole photon-mapping renders, one thread.
//
//   PhotonTrace/cornell/{global,caustic}   photons stored per second while tracing one map
//                                          (100,000 photons through a BVH; counters: photons/s,
//                                          paths/s, rays/s)
//   PhotonRender/{fig4_ring,fig5_glass_caustic,fig6_ring_cone_k1}
//                                          a whole render at 320x240 with the scene's knobs, and
//                                          its time split as counters (ms per render): tracing
//                                          photons, building maps, the render loop, and within
//                                          the loop gathers (kNN + density) and direct light
//
// Before anything is timed, each scene's photon maps through the BVH are checked to be the
// naive structure's, photon for photon, and its image bit-identical; a mismatch fails the
// benchmark with an error and makes the binary exit non-zero. Times are wall time of one thread
// (the photon tracer and the render loop run on `threads = 1`).
//
//   build/bin/bench_photon_render --benchmark_filter=PhotonTrace

#include "photon/photon_integrator.h"
#include "photon/photon_params.h"
#include "validated_main.h"

#include "scenes_gen/generators.h"

#include "tracer/render.h"

#include "accel/accel.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>
#include <string>

namespace {

using nlohmann::json;

int g_validation_failures = 0;

struct Prepared {
  tracer::Scene scene;
  accel::AnyAccel bvh;
  json knobs;  ///< Complete photon knobs: the scene's, with the benchmark's on top.
};

Prepared prepare(const std::string& generator, const json& overrides) {
  Prepared p;
  p.scene = scenes_gen::generate(generator, {});
  const auto boxes = p.scene.geometry.primitive_bounds();
  p.bvh = accel::make_accel("bvh", json::object(), boxes);
  json knobs = p.scene.integrator.knobs;
  for (auto it = overrides.begin(); it != overrides.end(); ++it) knobs[it.key()] = it.value();
  p.knobs = photon::photon_integrator().params(knobs);
  return p;
}

bool same(const std::vector<photon::Photon>& a, const std::vector<photon::Photon>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(photon::Photon)) == 0);
}

/// The BVH's photon maps and image equal naive's; on a mismatch, the benchmark errors out.
bool validate(benchmark::State& state, const Prepared& p, const tracer::RenderOptions& o) {
  const auto boxes = p.scene.geometry.primitive_bounds();
  const accel::AnyAccel naive = accel::make_accel("naive", json::object(), boxes);
  const photon::PhotonParams params = p.knobs.get<photon::PhotonParams>();
  const photon::PhotonMaps a = photon::make_photon_maps(p.scene, naive, params, o, true);
  const photon::PhotonMaps b = photon::make_photon_maps(p.scene, p.bvh, params, o, true);
  const bool maps_ok = same(a.global_pass.photons, b.global_pass.photons) &&
                       same(a.caustic_pass.photons, b.caustic_pass.photons);
  const auto ia = tracer::render(p.scene, naive, o, photon::photon_integrator(), p.knobs);
  const auto ib = tracer::render(p.scene, p.bvh, o, photon::photon_integrator(), p.knobs);
  if (maps_ok && ia.image.content_hash() == ib.image.content_hash() && ia.rays == ib.rays)
    return true;
  ++g_validation_failures;
  state.SkipWithError(maps_ok ? "the BVH's image differs from naive's"
                              : "the BVH's photon maps differ from naive's");
  return false;
}

void bm_trace(benchmark::State& state, std::string scene, photon::PhotonPass pass) {
  photon::PhotonParams maps;
  maps.global_photons = maps.caustic_photons = 100000;
  const Prepared p = prepare(scene, photon::PhotonParams::knobs().changed_json(maps));
  const photon::PhotonParams knobs = p.knobs.get<photon::PhotonParams>();
  photon::PassOptions o;
  o.pass = pass;
  o.target = 100000;
  o.threads = 1;
  o.max_depth = knobs.max_photon_depth;
  o.seed = knobs.seed;
  {
    const auto boxes = p.scene.geometry.primitive_bounds();
    const accel::AnyAccel naive = accel::make_accel("naive", json::object(), boxes);
    photon::PassOptions small = o;
    small.target = 5000;
    if (!same(photon::trace_photon_pass(p.scene, naive, small).photons,
              photon::trace_photon_pass(p.scene, p.bvh, small).photons)) {
      ++g_validation_failures;
      state.SkipWithError("the BVH's photons differ from naive's");
      return;
    }
  }
  std::uint64_t photons = 0, paths = 0, rays = 0;
  for (auto _ : state) {
    const photon::PassResult r = photon::trace_photon_pass(p.scene, p.bvh, o);
    photons += r.photons.size();
    paths += r.emitted;
    rays += r.rays;
    benchmark::DoNotOptimize(r.photons.data());
  }
  state.counters["photons/s"] = benchmark::Counter(double(photons), benchmark::Counter::kIsRate);
  state.counters["paths/s"] = benchmark::Counter(double(paths), benchmark::Counter::kIsRate);
  state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
}

void bm_render(benchmark::State& state, std::string scene, json overrides) {
  const Prepared p = prepare(scene, overrides);
  tracer::RenderOptions o;
  o.threads = 1;
  o.width = 320;
  o.height = 240;
  {
    tracer::RenderOptions small = o;
    small.width = 80;
    small.height = 60;
    if (!validate(state, p, small)) return;
  }
  double trace = 0, build = 0, loop = 0, gather = 0, direct = 0;
  for (auto _ : state) {
    const tracer::RenderResult r = tracer::render(p.scene, p.bvh, o, photon::photon_integrator(), p.knobs);
    const json& t = r.stats["timings"];
    trace += t["photon_trace_ms"].get<double>();
    build += t["map_build_ms"].get<double>();
    loop += t["render_loop_ms"].get<double>();
    gather += t["gather_thread_ms"].get<double>();
    direct += t["direct_thread_ms"].get<double>();
  }
  const auto avg = benchmark::Counter::kAvgIterations;
  state.counters["trace_ms"] = benchmark::Counter(trace, avg);
  state.counters["build_ms"] = benchmark::Counter(build, avg);
  state.counters["loop_ms"] = benchmark::Counter(loop, avg);
  state.counters["gather_ms"] = benchmark::Counter(gather, avg);
  state.counters["direct_ms"] = benchmark::Counter(direct, avg);
}

void register_benchmarks() {
  benchmark::RegisterBenchmark("PhotonTrace/cornell/global", bm_trace, std::string("cornell"),
                               photon::PhotonPass::Global)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("PhotonTrace/cornell/caustic", bm_trace, std::string("cornell"),
                               photon::PhotonPass::Caustic)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("PhotonRender/fig4_ring", bm_render, std::string("ring"), json::object())
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("PhotonRender/fig5_glass_caustic", bm_render,
                               std::string("glass_caustic"), json::object())
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  photon::PhotonParams sharpest;
  sharpest.cone_k = 1.0f;
  benchmark::RegisterBenchmark("PhotonRender/fig6_ring_cone_k1", bm_render, std::string("ring"),
                               photon::PhotonParams::knobs().changed_json(sharpest))
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
}

}  // namespace

int main(int argc, char** argv) {
  return bench::run_validated_benchmarks(
      argc, argv, register_benchmarks, g_validation_failures,
      "bench_photon_render: %d benchmark(s) failed validation against naive\n");
}
