// Google Benchmark: whole renders of every registered generator's scene and of every registered
// integrator, one thread, so that a generator or an integrator is measured as soon as its
// registry line exists (tests/registry_test.cpp checks that every one has its row).
//
//   Generator/<name>             the generator's scene at its defaults, through `auto` (the
//                                command line's default structure), rendered at 160x120 by the
//                                integrator the scene names (whitted when it names none);
//                                counters: generate_ms and build_ms (once), primitives
//   Integrator/<name>/cornell    the Cornell box at 160x120 through a bvh, by each integrator at
//                                its default knobs
//
// Before anything is timed, the structure is checked against naive: a generator's scene by a
// Whitted render at 32x24 (camera, shadow, reflected and refracted rays), an integrator's by its
// own render at 32x24; the images must be bit-identical and the ray counts equal. A mismatch
// fails the benchmark with an error and makes the binary exit non-zero. The mesh generators are
// registered only when ../shared/meshes is there.
//
//   build/bin/bench_render --benchmark_filter='^Generator/'

#include "validated_main.h"

#include "integrators/integrators.h"
#include "scenes_gen/generators.h"
#include "scenes_gen/mesh_scenes.h"
#include "tracer/build_accel.h"
#include "tracer/render.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace {

using nlohmann::json;

int g_validation_failures = 0;

constexpr int kWidth = 160, kHeight = 120;       ///< The timed renders.
constexpr int kCheckWidth = 32, kCheckHeight = 24;  ///< The renders checked against naive.

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

tracer::RenderOptions one_thread(int width, int height) {
  tracer::RenderOptions o;
  o.threads = 1;
  o.width = width;
  o.height = height;
  return o;
}

/// True when `structure` renders `scene` at the check size as naive does, bit for bit; otherwise
/// fails the benchmark.
bool same_as_naive(benchmark::State& state, const tracer::Scene& scene, const accel::AnyAccel& structure,
                   const tracer::Integrator& integrator, const json& params) {
  const auto boxes = scene.geometry.primitive_bounds();
  const accel::AnyAccel naive = tracer::build_accel("naive", json::object(), scene.geometry, boxes);
  const tracer::RenderOptions o = one_thread(kCheckWidth, kCheckHeight);
  const tracer::RenderResult want = tracer::render(scene, naive, o, integrator, params);
  const tracer::RenderResult got = tracer::render(scene, structure, o, integrator, params);
  if (got.image.content_hash() == want.image.content_hash() && got.rays == want.rays) return true;
  ++g_validation_failures;
  state.SkipWithError(("validation failed: " + accel::name_of(structure) + "'s " + std::string(integrator.name) +
                       " image differs from naive's")
                          .c_str());
  return false;
}

/// Times `integrator` rendering `scene` through `structure` at 160x120 on one thread.
void time_renders(benchmark::State& state, const tracer::Scene& scene, const accel::AnyAccel& structure,
                  const tracer::Integrator& integrator, const json& params) {
  const tracer::RenderOptions o = one_thread(kWidth, kHeight);
  std::uint64_t rays = 0;
  for (auto _ : state) {
    const tracer::RenderResult r = tracer::render(scene, structure, o, integrator, params);
    rays = r.rays.total();
    benchmark::DoNotOptimize(r.image.content_hash());
  }
  state.counters["rays_per_render"] = double(rays);
  state.SetLabel(std::string(integrator.name) + " through " + accel::name_of(structure) + " " +
                 accel::params_of(structure).dump());
}

void bm_generator(benchmark::State& state, const std::string& name) {
  const auto t0 = std::chrono::steady_clock::now();
  const tracer::Scene scene = scenes_gen::generate(name, {});
  const double generate_ms = ms_since(t0);
  const auto boxes = scene.geometry.primitive_bounds();
  const auto t1 = std::chrono::steady_clock::now();
  const accel::AnyAccel structure = tracer::build_accel("auto", json::object(), scene.geometry, boxes);
  const double build_ms = ms_since(t1);
  if (!same_as_naive(state, scene, structure, tracer::whitted_integrator(), json::object())) return;
  const integrators::Setup setup = integrators::resolve(scene, name, "", "", json::object(), "");
  time_renders(state, scene, structure, *setup.integrator, setup.params);
  state.counters["generate_ms"] = generate_ms;
  state.counters["build_ms"] = build_ms;
  state.counters["primitives"] = double(boxes.size());
}

void bm_integrator(benchmark::State& state, const tracer::Integrator* integrator) {
  const tracer::Scene scene = scenes_gen::generate("cornell", {});
  const accel::AnyAccel structure =
      tracer::build_accel("bvh", json::object(), scene.geometry, scene.geometry.primitive_bounds());
  const json params = integrator->params(json::object());
  if (!same_as_naive(state, scene, structure, *integrator, params)) return;
  time_renders(state, scene, structure, *integrator, params);
}

void register_benchmarks() {
  bool meshes = true;
  try {
    scenes_gen::model_path("bunny");
  } catch (const scenes_gen::GenError& e) {
    std::fprintf(stderr, "bench_render: %s; the mesh generators are left out\n", e.what());
    meshes = false;
  }
  for (const std::string& name : scenes_gen::generator_names()) {
    if (scenes_gen::generator_takes_model(name) && !meshes) continue;
    benchmark::RegisterBenchmark(("Generator/" + name).c_str(), bm_generator, name)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  for (const tracer::Integrator* i : integrators::all())
    benchmark::RegisterBenchmark(("Integrator/" + std::string(i->name) + "/cornell").c_str(), bm_integrator, i)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
}

}  // namespace

int main(int argc, char** argv) {
  return bench::run_validated_benchmarks(argc, argv, register_benchmarks, g_validation_failures,
                                         "bench_render: %d benchmark(s) failed validation against naive\n");
}
