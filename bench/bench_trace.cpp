// Google Benchmark: closest-hit tracing through every structure on the paper's scenes and on
// triangle meshes (bunny, ogre, nefertiti: shared standard models; grid1M: a million triangles of
// instanced bunnies; present with ../shared/meshes), one thread, 1024x768 camera rays (coherent;
// and packets: the same rays by 4x4-pixel tiles, 16 at a time through the structures that
// traverse packets) and rays spawned off the camera hits (incoherent); any-hit queries of the
// shadow rays from the camera hits to every light (shadow); whole renders (Render/: Whitted on
// spheres8000 at 1024x768 and the meshes at 640x480, the SPD scenes at 256x256, all ray kinds,
// one thread; RenderPair/: the same renders paired with each peer's (embree, and Embree's own
// spheres or triangles where the scene is made of them), render by render); plus build times
// over a grid of knobs.
//
// Every structure's hits are validated against naive before it is timed, on the path it times
// (single rays, packets, any-hit queries; Embree at the ISA it is timed at): all rays, same
// primitive, bit-equal t; a structure with its own primitive routine (embree_points,
// embree_triangles) within a tolerance (another primitive, any-hit answer or a t more than 1e-5
// relative off for at most 0.1% of rays, every hit point within 1e-5 of its coordinates of naive's
// surface, along its normal; its hits within the rounding of a ray's own origin are counted apart,
// as peer_self_hits). A mismatch skips that benchmark with an error and makes the binary exit
// non-zero. A whole render is validated by rendering a window of the image through naive and
// through the structure: every pixel bit-equal.
// Naive's reference pass (8000 spheres x 786k rays, about 7 s) is computed once per process and
// shared; naive itself is timed on every 64th ray of spheres8000, which is what its rate and the
// speedup counters are based on (the counter names say so). On the meshes naive would take hours:
// the reference on every ray is the binary BVH's, checked bit for bit against naive's on every 64th
// ray or sparser (near 10^9 box tests), and a mismatch stops the run. Times and rates are CPU time
// of the tracing thread, so other processes on a shared machine do not count.
//
//   build/bin/bench_trace --benchmark_filter='Trace/spheres8000'

#include "accel/accel.h"
#include "accel/build_threads.h"
#include "bench_rays.h"
#include "bench_scenes.h"
#include "bench_validation.h"
#include "scenes_gen/generators.h"
#include "scenes_gen/mesh_scenes.h"
#include "tracer/build_accel.h"
#include "tracer/image_compare.h"
#include "tracer/intersector.h"
#include "tracer/render.h"
#include "tracer/scene_io.h"
#include "validated_main.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <ctime>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace {

using accel::Ray;
using accel::Vec3;
using nlohmann::json;
using tracer::Hit;
using bench::blocked_mismatch;
using bench::hit_mismatch;
using bench::is_exact;
using bench::is_mesh_scene;
using bench::kBuildOnlyMeshScene;
using bench::kMeshScenes;
using bench::kSpotGrids;
using bench::kTessellated;
using bench::Validation;

constexpr int kWidth = 1024;
constexpr int kHeight = 768;
/// naive on spheres8000 is timed on every kNaiveStride-th ray.
constexpr std::size_t kNaiveStride = 64;

int g_validation_failures = 0;

/// Camera rays, the same rays in 4x4-pixel tiles traced as packets of 16, rays spawned off
/// their hits, and shadow rays (any-hit queries) to the lights.
enum class RaySet { Coherent, Packets, Incoherent, Shadow };
const char* ray_set_name(RaySet s) {
  switch (s) {
    case RaySet::Coherent: return "coherent";
    case RaySet::Packets: return "packets";
    case RaySet::Incoherent: return "incoherent";
    case RaySet::Shadow: return "shadow";
  }
  return "?";
}

/// Side of the square pixel tile whose camera rays form one packet.
constexpr int kTile = 4;

/// Traces `rays` (closest hit) through one structure; the render loop is compiled per structure.
void trace(const tracer::Geometry& geometry, const accel::AnyAccel& a, const std::vector<Ray>& rays,
           std::vector<Hit>& hits) {
  hits.resize(rays.size());
  tracer::with_intersector<false>(geometry, a, tracer::TriangleTest::Watertight, [&](const auto& isect) {
    for (std::size_t i = 0; i < rays.size(); ++i) hits[i] = isect.closest(rays[i]);
  });
}

/// Traces `rays` as packets of 16 consecutive rays (closest hit): structures with a packet
/// traversal take each packet at once, the others ray by ray.
void trace_packets(const tracer::Geometry& geometry, const accel::AnyAccel& a, const std::vector<Ray>& rays,
                   std::vector<Hit>& hits) {
  hits.resize(rays.size());
  tracer::with_intersector<false>(geometry, a, tracer::TriangleTest::Watertight, [&](const auto& isect) {
    constexpr std::size_t kPacket = std::decay_t<decltype(isect)>::kPacketMax;
    for (std::size_t i = 0; i < rays.size(); i += kPacket) {
      const std::size_t n = std::min(kPacket, rays.size() - i);
      isect.closest_packet(std::span<const Ray>(rays.data() + i, n), std::span<Hit>(hits.data() + i, n));
    }
  });
}

/// Answers any-hit queries of `rays` through one structure: 1 where something blocks the ray.
void occlude(const tracer::Geometry& geometry, const accel::AnyAccel& a, const std::vector<Ray>& rays,
             std::vector<std::uint8_t>& blocked) {
  blocked.resize(rays.size());
  tracer::with_intersector<false>(geometry, a, tracer::TriangleTest::Watertight, [&](const auto& isect) {
    for (std::size_t i = 0; i < rays.size(); ++i) blocked[i] = isect.occluded(rays[i]);
  });
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// CPU time of this thread, seconds: what the rates are based on, so that other processes on a
/// shared machine do not count against a structure.
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

/// One ray set of one scene with its naive reference, computed on first use.
struct RayData {
  std::vector<Ray> rays;
  std::vector<Hit> reference;       ///< naive's hits, for validation (closest-hit sets).
  std::vector<std::uint8_t> blocked;  ///< naive's any-hit answers, for validation (shadow set).
  std::vector<Ray> naive_sample;    ///< The rays naive is timed on.
  double naive_s_per_ray = 0.0;     ///< naive's best time per ray on the sample.
  std::size_t naive_stride = 1;
};

struct BenchScene {
  tracer::Scene scene;
  std::vector<accel::Aabb> boxes;
  std::map<RaySet, std::unique_ptr<RayData>> sets;
};

/// A benchmark scene by name (bench_scene), generated once per process.
BenchScene& scene_named(const std::string& name) {
  static std::map<std::string, std::unique_ptr<BenchScene>> cache;
  auto& slot = cache[name];
  if (!slot) {
    slot = std::make_unique<BenchScene>();
    slot->scene = bench::bench_scene(name);
    slot->boxes = slot->scene.geometry.primitive_bounds();
  }
  return *slot;
}

/// Every kNaiveStride-th ray on ordinary scenes; on the meshes as many more as keep naive's
/// work (rays x primitives) near 10^9 box tests, so that its reference takes seconds, not hours.
std::size_t naive_stride_for(const std::string& scene_name, std::size_t primitives, std::size_t rays) {
  if (primitives <= 1000) return 1;
  if (!is_mesh_scene(scene_name)) return kNaiveStride;
  return std::max(kNaiveStride, std::bit_ceil(std::size_t(double(primitives) * double(rays) / 1e9) + 1));
}

/// The reference and naive timing of a ray set, computed once per process.
RayData& ray_data(const std::string& scene_name, RaySet set) {
  BenchScene& bs = scene_named(scene_name);
  auto& slot = bs.sets[set];
  if (slot) return *slot;
  auto d = std::make_unique<RayData>();
  if (set == RaySet::Coherent) {
    d->rays = bench::camera_rays(bs.scene, kWidth, kHeight);
  } else if (set == RaySet::Packets) {
    // The camera rays reordered tile by tile, with their reference and naive's timing.
    const RayData& primary = ray_data(scene_name, RaySet::Coherent);
    for (int ty = 0; ty < kHeight; ty += kTile)
      for (int tx = 0; tx < kWidth; tx += kTile)
        for (int y = ty; y < ty + kTile; ++y)
          for (int x = tx; x < tx + kTile; ++x) {
            const std::size_t i = std::size_t(y) * kWidth + std::size_t(x);
            d->rays.push_back(primary.rays[i]);
            d->reference.push_back(primary.reference[i]);
          }
    d->naive_sample = primary.naive_sample;
    d->naive_s_per_ray = primary.naive_s_per_ray;
    d->naive_stride = primary.naive_stride;
    slot = std::move(d);
    return *slot;
  } else if (set == RaySet::Incoherent) {
    const RayData& primary = ray_data(scene_name, RaySet::Coherent);
    d->rays = bench::spawned_rays(bs.scene.geometry, primary.rays, primary.reference);
  } else {
    const RayData& primary = ray_data(scene_name, RaySet::Coherent);
    d->rays = bench::shadow_rays(bs.scene, primary.rays, primary.reference);
  }
  const bool any_hit = set == RaySet::Shadow;
  const tracer::Geometry& g = bs.scene.geometry;
  const accel::AnyAccel naive = accel::make_accel("naive", nullptr, bs.boxes);
  d->naive_stride = naive_stride_for(scene_name, bs.boxes.size(), d->rays.size());
  for (std::size_t i = 0; i < d->rays.size(); i += d->naive_stride) d->naive_sample.push_back(d->rays[i]);
  // The reference on every ray: naive's own, or on the meshes the binary BVH's (bit-identical to
  // naive's in the oracle and image tests), checked bit for bit against naive's on the sample below.
  const bool chained = is_mesh_scene(scene_name);
  const auto t0 = std::chrono::steady_clock::now();
  std::fprintf(stderr, "bench_trace: %s reference for %s/%s (%zu rays)...\n", chained ? "bvh" : "naive",
               scene_name.c_str(), ray_set_name(set), d->rays.size());
  const accel::AnyAccel reference = chained ? tracer::build_accel("bvh", nullptr, g, bs.boxes) : accel::AnyAccel();
  const accel::AnyAccel& ref = chained ? reference : naive;
  if (any_hit)
    occlude(g, ref, d->rays, d->blocked);
  else
    trace(g, ref, d->rays, d->reference);
  std::fprintf(stderr, "bench_trace: done in %.1f s\n", seconds_since(t0));

  std::vector<Hit> scratch;
  std::vector<std::uint8_t> scratch_blocked;
  double best = 1e30;
  for (int rep = 0; rep < 3; ++rep) {
    const double t1 = thread_cpu_seconds();
    if (any_hit)
      occlude(g, naive, d->naive_sample, scratch_blocked);
    else
      trace(g, naive, d->naive_sample, scratch);
    best = std::min(best, thread_cpu_seconds() - t1);
  }
  if (chained) {
    std::size_t bad = 0;
    for (std::size_t k = 0; k < d->naive_sample.size(); ++k) {
      const std::size_t i = k * d->naive_stride;
      bad += any_hit ? scratch_blocked[k] != d->blocked[i]
                     : scratch[k].prim != d->reference[i].prim ||
                           std::bit_cast<std::uint32_t>(scratch[k].t) != std::bit_cast<std::uint32_t>(d->reference[i].t);
    }
    if (bad) {
      std::fprintf(stderr, "bench_trace: the bvh reference for %s/%s differs from naive on %zu of %zu sampled rays\n",
                   scene_name.c_str(), ray_set_name(set), bad, d->naive_sample.size());
      std::exit(1);
    }
  }
  d->naive_s_per_ray = best / double(d->naive_sample.size());
  slot = std::move(d);
  return *slot;
}

/// Builds a structure, or skips the benchmark with the factory's message.
bool build_or_skip(benchmark::State& state, const std::string& name, const json& knobs,
                   const BenchScene& bs, accel::AnyAccel& out) {
  try {
    out = tracer::build_accel(name, knobs, bs.scene.geometry, bs.boxes);
    return true;
  } catch (const knobs::ConfigError& e) {
    state.SkipWithError(e.what());
    return false;
  }
}

/// Times closest-hit tracing (any-hit queries for the shadow set) of one ray set through one
/// structure, after validating it.
void bm_trace(benchmark::State& state, const std::string& scene_name, RaySet set,
              const std::string& name, const json& knobs) {
  BenchScene& bs = scene_named(scene_name);
  RayData& d = ray_data(scene_name, set);
  accel::AnyAccel a;
  if (!build_or_skip(state, name, knobs, bs, a)) return;
  const bool is_naive = name == "naive";
  const std::vector<Ray>& rays = is_naive ? d.naive_sample : d.rays;

  const bool any_hit = set == RaySet::Shadow;
  std::vector<Hit> hits;
  std::vector<std::uint8_t> blocked;
  if (!is_naive) {
    // The exact path the loop below times, on every ray it times.
    const bool exact = is_exact(name);
    Validation v;
    if (any_hit) {
      occlude(bs.scene.geometry, a, rays, blocked);
      v = blocked_mismatch(rays, blocked, d.blocked, exact, [&](const Ray& r) {
        std::vector<Hit> one;
        trace(bs.scene.geometry, a, {r}, one);
        return one[0].t;
      });
    } else if (set == RaySet::Packets) {
      trace_packets(bs.scene.geometry, a, rays, hits);
      v = hit_mismatch(bs.scene.geometry, rays, hits, d.reference, exact);
    } else {
      trace(bs.scene.geometry, a, rays, hits);
      v = hit_mismatch(bs.scene.geometry, rays, hits, d.reference, exact);
    }
    if (!v.why.empty()) {
      ++g_validation_failures;
      state.SkipWithError(("validation failed: " + v.why).c_str());
      return;
    }
    if (!exact) state.counters["peer_self_hits"] = double(v.self_hits);
  }
  const double cpu0 = thread_cpu_seconds();
  for (auto _ : state) {
    if (any_hit) {
      occlude(bs.scene.geometry, a, rays, blocked);
      benchmark::DoNotOptimize(blocked.data());
    } else if (set == RaySet::Packets && !is_naive) {
      trace_packets(bs.scene.geometry, a, rays, hits);
      benchmark::DoNotOptimize(hits.data());
    } else {
      trace(bs.scene.geometry, a, rays, hits);
      benchmark::DoNotOptimize(hits.data());
    }
    benchmark::ClobberMemory();
  }
  const double cpu = thread_cpu_seconds() - cpu0;
  const double n = double(rays.size()) * double(state.iterations());
  // A rate counter divides by the benchmark's CPU time (no UseRealTime): rays per CPU second.
  state.counters["rays"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
  const std::string sample = "(naive_on_1/" + std::to_string(d.naive_stride) + "_of_rays)";
  // naive's CPU time per ray over this structure's, each from its own timing.
  state.counters["speedup_vs_naive" + sample] = cpu > 0.0 ? d.naive_s_per_ray * n / cpu : 0.0;
  state.SetLabel(accel::name_of(a) + " " + accel::params_of(a).dump());
}

/// CPU time of the whole process, seconds: a render's worker threads included, other
/// processes excluded.
double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

/// A whole-render workload: a scene, its integrator and the image size.
struct RenderCase {
  std::string label;   ///< Benchmark name part: scene name or SPD file stem.
  std::string path;    ///< Scene file; empty for a generated scene (label).
  bool spd = false;    ///< SPD rules (spd integrator) instead of Whitted.
  int width = 0, height = 0;
};

/// The scene of a render case with its boxes, loaded once.
BenchScene& render_scene(const RenderCase& rc) {
  if (rc.path.empty()) return scene_named(rc.label);
  static std::map<std::string, std::unique_ptr<BenchScene>> cache;
  auto& slot = cache[rc.path];
  if (!slot) {
    slot = std::make_unique<BenchScene>();
    slot->scene = tracer::load_scene_file(rc.path);
    slot->boxes = slot->scene.geometry.primitive_bounds();
  }
  return *slot;
}

/// A render case's scene, integrator and one-thread options.
struct RenderSetup {
  BenchScene* scene = nullptr;
  const tracer::Integrator* integrator = nullptr;
  tracer::RenderOptions options;
};

/// Loads the scene of `rc` (cached); false, with the benchmark skipped, if that fails.
bool render_setup(benchmark::State& state, const RenderCase& rc, RenderSetup& out) {
  try {
    out.scene = &render_scene(rc);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return false;
  }
  out.integrator = rc.spd ? &tracer::spd_integrator() : &tracer::whitted_integrator();
  out.options.threads = 1;
  out.options.width = rc.width;
  out.options.height = rc.height;
  return true;
}

/// Builds structure `name` for the render and renders the image window in the middle of the
/// frame through it and through naive: they must be bit-equal. False, with the benchmark skipped
/// (and counted as a validation failure if the images differ), otherwise.
bool build_validated_render(benchmark::State& state, const RenderCase& rc, const RenderSetup& setup,
                            const std::string& name, const json& knobs, accel::AnyAccel& a) {
  BenchScene& bs = *setup.scene;
  if (!build_or_skip(state, name, knobs, bs, a)) return false;
  // Validation window: 48 x 48 pixels at the centre.
  tracer::RenderOptions window = setup.options;
  window.window = {rc.width / 2 - 24, rc.height / 2 - 24, rc.width / 2 + 24, rc.height / 2 + 24};
  static std::map<std::string, tracer::Image> naive_windows;
  auto& want = naive_windows[rc.label];
  if (want.pixels().empty()) {
    accel::AnyAccel naive = accel::make_accel("naive", nullptr, bs.boxes);
    want = tracer::render(bs.scene, naive, window, *setup.integrator).image;
  }
  const tracer::Image got = tracer::render(bs.scene, a, window, *setup.integrator).image;
  const bool same_size = got.pixels().size() == want.pixels().size();
  if (is_exact(name)) {
    if (!same_size ||
        std::memcmp(got.pixels().data(), want.pixels().data(), want.pixels().size() * sizeof(tracer::Image::Pixel)) != 0) {
      ++g_validation_failures;
      state.SkipWithError(("validation failed: " + name + "'s centre window differs from naive's render").c_str());
      return false;
    }
  } else if (!same_size || tracer::compare_images(got, want).fraction_off > tracer::kPeerPixelsOffShare) {
    ++g_validation_failures;
    state.SkipWithError(("validation failed: more than 2% of " + name +
                         "'s centre window is more than 1% off naive's render").c_str());
    return false;
  }
  return true;
}

/// One timed render: the process's CPU seconds (other processes do not count) and its rays.
double timed_render(const RenderSetup& setup, const accel::AnyAccel& a, std::uint64_t& rays) {
  const double t0 = process_cpu_seconds();
  const tracer::RenderResult r = tracer::render(setup.scene->scene, a, setup.options, *setup.integrator);
  const double seconds = process_cpu_seconds() - t0;
  rays = r.rays.total();
  benchmark::DoNotOptimize(r.image.pixels().data());
  return seconds;
}

/// One thread, the whole image, all ray kinds, validated against naive first. Times are the
/// process's CPU time per render (manual time).
void bm_render(benchmark::State& state, const RenderCase& rc, const std::string& name, const json& knobs) {
  RenderSetup setup;
  accel::AnyAccel a;
  if (!render_setup(state, rc, setup) || !build_validated_render(state, rc, setup, name, knobs, a)) return;
  std::uint64_t rays = 0;
  for (auto _ : state) state.SetIterationTime(timed_render(setup, a, rays));
  state.counters["rays_per_render"] = double(rays);
  state.SetLabel(accel::name_of(a) + " " + accel::params_of(a).dump());
}

/// The same render through one of our structures and through a peer (Embree), in pairs: each
/// iteration renders with both, back to back, the peer first in every other pair. The time is the
/// structure's; the counter `peer_ms_over_this` is the peer's time over the structure's summed
/// over this repetition's pairs, so its median over the repetitions is a ratio of renders taken
/// back to back (well under a second apart). A slow spell of the host (tens of seconds) then
/// slows both sides of a ratio, where it can decide the ratio of the two separate Render
/// benchmarks' medians.
void bm_render_pair(benchmark::State& state, const RenderCase& rc, const std::string& name, const json& knobs,
                    const std::string& peer, const std::shared_ptr<int>& pairs_so_far) {
  RenderSetup setup;
  accel::AnyAccel a, other;
  if (!render_setup(state, rc, setup) || !build_validated_render(state, rc, setup, name, knobs, a) ||
      !build_validated_render(state, rc, setup, peer, json::object(), other))
    return;
  int& pair = *pairs_so_far;  // over all repetitions of this benchmark, to alternate the order
  double this_s = 0, peer_s = 0;
  std::uint64_t rays = 0, peer_rays = 0;
  for (auto _ : state) {
    double t = 0, e = 0;
    if (pair++ % 2 == 0) {
      t = timed_render(setup, a, rays);
      e = timed_render(setup, other, peer_rays);
    } else {
      e = timed_render(setup, other, peer_rays);
      t = timed_render(setup, a, rays);
    }
    state.SetIterationTime(t);
    this_s += t;
    peer_s += e;
  }
  if (is_exact(peer) && rays != peer_rays) {
    ++g_validation_failures;
    state.SkipWithError(("validation failed: the structure and " + peer + " traced different numbers of rays").c_str());
    return;
  }
  state.counters["rays_per_render"] = double(rays);
  state.counters["peer_ms_over_this"] = this_s > 0 ? peer_s / this_s : 0.0;
  state.SetLabel(accel::name_of(a) + " " + accel::params_of(a).dump() + " against " + peer);
}

/// Times building one structure with (max_depth, max_leaf_size) from the benchmark arguments.
void bm_build(benchmark::State& state, const std::string& scene_name, const std::string& name,
              json knobs) {
  const BenchScene& bs = scene_named(scene_name);
  knobs["max_depth"] = state.range(0);
  knobs["max_leaf_size"] = state.range(1);
  accel::AnyAccel a;
  if (!build_or_skip(state, name, knobs, bs, a)) return;
  for (auto _ : state) {
    a = tracer::build_accel(name, knobs, bs.scene.geometry, bs.boxes);
    benchmark::DoNotOptimize(&a);
  }
  const accel::BuildStats& s = accel::stats_of(a);
  state.counters["nodes"] = double(s.nodes);
  state.counters["sah_cost"] = s.sah_cost;
  state.counters["duplication"] = s.duplication();
  state.counters["memory_MiB"] = double(s.memory_bytes) / double(1 << 20);
}

/// Times building one structure at its default knobs, the scene's spheres or triangles attached
/// (what a render builds); memory per primitive as a counter.
void bm_build_default(benchmark::State& state, const std::string& scene_name, const std::string& name,
                      const json& knobs) {
  const BenchScene& bs = scene_named(scene_name);
  accel::AnyAccel a;
  if (!build_or_skip(state, name, knobs, bs, a)) return;
  for (auto _ : state) {
    a = accel::AnyAccel();
    a = tracer::build_accel(name, knobs, bs.scene.geometry, bs.boxes);
    benchmark::DoNotOptimize(&a);
  }
  const accel::BuildStats& s = accel::stats_of(a);
  state.counters["nodes"] = double(s.nodes);
  state.counters["bytes_per_prim"] = double(s.memory_bytes) / double(std::max<std::size_t>(bs.boxes.size(), 1));
  state.counters["primitives"] = double(bs.boxes.size());
  // The structure's own build time: for Embree's native peers, the native build alone (their
  // stats_note), where the time above also counts the user-geometry build and copies before it.
  state.counters["reported_build_ms"] = s.build_ms;
  state.SetLabel(accel::name_of(a) + " " + accel::params_of(a).dump());
}

/// Trace time over the tree knobs (max_depth, max_leaf_size) from the benchmark arguments.
void bm_trace_knobs(benchmark::State& state, RaySet set, const std::string& name, json knobs) {
  knobs["max_depth"] = state.range(0);
  knobs["max_leaf_size"] = state.range(1);
  bm_trace(state, "spheres8000", set, name, knobs);
}

/// A structure as the benchmarks name it: factory name plus knobs.
struct Config {
  std::string label;
  std::string name;
  json knobs;
  std::vector<std::string> knob_names;  ///< Every knob the structure has.
  bool meshes_only = false;             ///< A row for the mesh scenes only.

  bool has_knob(const std::string& k) const {
    return std::find(knob_names.begin(), knob_names.end(), k) != knob_names.end();
  }
};

/// From the registry: every structure built here at its defaults, plus one configuration per
/// other value of each knob that changes the algorithm (KnobTable variant knobs: kdtree_sah,
/// octree_every_level, ...).
std::vector<Config> trace_configs() {
  std::vector<Config> out;
  for (const accel::StructureInfo& s : accel::structures()) {
    if (!s.built) continue;
    out.push_back({s.name, s.name, json::object(), s.knobs});
    // Embree's watertight mode and its high-quality build (spatial splits) beside its default
    // build, on the meshes.
    if (s.name == accel::EmbreeTriangles::kName) {
      accel::EmbreeTrianglesParams robust, high;
      robust.robust = true;
      high.build_quality = accel::EmbreeQuality::High;
      const auto& table = accel::EmbreeTrianglesParams::knobs();
      out.push_back({s.name + "_robust", s.name, table.changed_json(robust), s.knobs});
      out.push_back({s.name + "_high", s.name, table.changed_json(high), s.knobs});
    }
    // Spatial splits (SBVH) in our 8-wide BVH, against its plain build, on the meshes.
    if (s.name == accel::Bvh8::kName) {
      accel::Bvh8::Params spatial;
      spatial.spatial_split_budget = 0.25f;
      out.push_back({s.name + "_spatial", s.name, accel::Bvh8::Params::knobs().changed_json(spatial), s.knobs, true});
    }
    for (const json& k : s.knob_table) {
      if (!k.at("variant").get<bool>() || !k.contains("choices")) continue;
      for (const json& c : k.at("choices"))
        if (c != k.at("default"))
          out.push_back({s.name + "_" + c.get<std::string>(), s.name, {{k.at("name").get<std::string>(), c}}, s.knobs});
    }
  }
  return out;
}

/// The structures with both tree knobs (max_depth, max_leaf_size) that the knob grids vary.
std::vector<Config> tree_configs() {
  std::vector<Config> out;
  for (const Config& c : trace_configs())
    if (c.has_knob("max_depth") && c.has_knob("max_leaf_size") && !c.meshes_only) out.push_back(c);
  return out;
}

/// Milliseconds, and beside Google Benchmark's mean, median and spread over the repetitions
/// their minimum: on a host with slow spells of tens of seconds the median of a few
/// repetitions flips with where the spells fall, while the minimum is the time outside them.
benchmark::internal::Benchmark* timed_ms(benchmark::internal::Benchmark* b) {
  return b->Unit(benchmark::kMillisecond)->ComputeStatistics("min", [](const std::vector<double>& v) {
    return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end());
  });
}

/// Whether a structure is worth a row on a scene: a native peer only where its primitives are
/// the scene's (elsewhere it is the user-geometry adapter, `embree`, again).
bool applies(const std::string& structure, bool mesh_scene) {
  const accel::StructureInfo* info = accel::find_structure(structure);
  if (info == nullptr || info->native_shapes.empty()) return true;
  return info->native_shapes == (mesh_scene ? "triangles" : "spheres");
}

/// Whether a configuration gets a row on a scene: its structure applies and, for a meshes-only
/// row, the scene is a mesh.
bool applies(const Config& c, bool mesh_scene) { return (mesh_scene || !c.meshes_only) && applies(c.name, mesh_scene); }

/// The mesh scenes this run has (none without ../shared/meshes, with a message).
std::vector<std::string> available_mesh_scenes() {
  try {
    scenes_gen::model_path("bunny");
  } catch (const scenes_gen::GenError& e) {
    std::fprintf(stderr, "bench_trace: %s; the mesh benchmarks are left out\n", e.what());
    return {};
  }
  return kMeshScenes;
}

void register_benchmarks() {
  std::vector<std::string> trace_scenes = {"spheres8000", "five"};
  const std::vector<std::string> mesh_scenes = available_mesh_scenes();
  trace_scenes.insert(trace_scenes.end(), mesh_scenes.begin(), mesh_scenes.end());
  for (const std::string& scene : trace_scenes)
    for (RaySet set : {RaySet::Coherent, RaySet::Packets, RaySet::Incoherent, RaySet::Shadow})
      for (const Config& c : trace_configs()) {
        if (!applies(c, is_mesh_scene(scene))) continue;
        const std::string bm = "Trace/" + scene + "/" + ray_set_name(set) + "/" + c.label;
        timed_ms(benchmark::RegisterBenchmark(bm.c_str(), bm_trace, scene, set, c.name, c.knobs));
      }
  // Whole renders: spheres8000 (Whitted, 1024x768), every SPD scene (256x256) and the mesh
  // scenes (Whitted, 640x480).
  std::vector<RenderCase> renders = {{"spheres8000", "", false, kWidth, kHeight}};
  for (const std::string& scene : mesh_scenes) renders.push_back({scene, "", false, 640, 480});
  const std::filesystem::path spd_dir = ACCELBENCH_SPD_DIR;
  std::vector<std::filesystem::path> spd_files;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(spd_dir, ec))
    if (entry.path().extension() == ".nff") spd_files.push_back(entry.path());
  if (ec) std::fprintf(stderr, "bench_trace: no SPD scenes (%s: %s); their Render benchmarks are left out\n",
                       spd_dir.string().c_str(), ec.message().c_str());
  std::sort(spd_files.begin(), spd_files.end());
  for (const auto& f : spd_files) renders.push_back({f.stem().string(), f.string(), true, 256, 256});
  const std::vector<Config> configs = trace_configs();
  std::vector<std::string> peers;  // the structures we measure against (Embree's), built here
  for (const accel::StructureInfo& s : accel::structures())
    if (s.peer && s.built) peers.push_back(s.name);
  for (const RenderCase& rc : renders)
    for (const Config& c : configs) {
      if (c.name == "naive" || !applies(c, is_mesh_scene(rc.label))) continue;  // naive: hours per render
      const std::string bm = "Render/" + rc.label + "/" + c.label;
      timed_ms(benchmark::RegisterBenchmark(bm.c_str(), bm_render, rc, c.name, c.knobs)
          ->UseManualTime()
          ->Iterations(rc.path.empty() ? 1 : 3)
          );
      if (accel::find_structure(c.name)->peer) continue;
      for (const std::string& peer : peers) {
        if (!applies(peer, is_mesh_scene(rc.label))) continue;
        const std::string paired = "RenderPair/" + rc.label + "/" + c.label + "/vs_" + peer;
        timed_ms(benchmark::RegisterBenchmark(paired.c_str(), bm_render_pair, rc, c.name, c.knobs, peer,
                                              std::make_shared<int>(0))
            ->UseManualTime()
            ->Iterations(rc.path.empty() ? 1 : 3)
            );
      }
    }
  for (RaySet set : {RaySet::Coherent, RaySet::Packets, RaySet::Incoherent, RaySet::Shadow})
    for (const Config& c : tree_configs()) {
      const std::string bm = std::string("TraceKnobs/spheres8000/") + ray_set_name(set) + "/" + c.label;
      timed_ms(benchmark::RegisterBenchmark(bm.c_str(), bm_trace_knobs, set, c.name, c.knobs)
          ->ArgNames({"max_depth", "max_leaf_size"})
          ->ArgsProduct({{8, 16, 64}, {1, 2, 4, 8, 16}})
          );
    }
  // Build time at default knobs, every structure (Embree included), and on a million spheres and
  // the meshes: there the BVHs and Embree only.
  std::vector<std::string> build_scenes = {"spheres8000", "random1M"};
  build_scenes.insert(build_scenes.end(), mesh_scenes.begin(), mesh_scenes.end());
  for (const std::string& scene : build_scenes)
    for (const Config& c : trace_configs()) {
      const bool large = scene != "spheres8000";
      if (!applies(c, is_mesh_scene(scene)) ||
          (large && c.name != "bvh" && c.name != "bvh4" && c.name != "bvh8" && c.name != "embree" &&
           c.name != "embree_triangles"))
        continue;
      const std::string bm = "BuildDefault/" + scene + "/" + c.label;
      timed_ms(benchmark::RegisterBenchmark(bm.c_str(), bm_build_default, scene, c.name, c.knobs)
          );
    }
  // Build time on one thread and on two, at default knobs otherwise, for the BVHs and Embree's
  // native triangles on the large meshes: the builds' scaling targets.
  if (!mesh_scenes.empty())
    for (const std::string& scene : {std::string("grid1M"), kBuildOnlyMeshScene})
      for (const char* name : {"bvh", "bvh4", "bvh8", "embree_triangles"})
        for (int threads : {1, 2}) {
          if (!accel::find_structure(name)->built) continue;
          const std::string bm = "BuildThreads/" + scene + "/" + name + "/threads:" + std::to_string(threads);
          timed_ms(benchmark::RegisterBenchmark(bm.c_str(), bm_build_default, scene, std::string(name),
                                                json{{accel::kBuildThreadsKnob, threads}}));
        }
  // The scaling figure (scripts/plot_triangle_scaling.py): every structure at its defaults and
  // the SAH kd-tree, on spot grids and tessellated spheres of 5,856 to 10^7 triangles: build
  // time and bytes, camera and incoherent rays.
  if (!mesh_scenes.empty()) {
    std::vector<std::string> scaling_scenes;
    for (const auto& s : kSpotGrids) scaling_scenes.push_back(s.first);
    for (const auto& s : kTessellated) scaling_scenes.push_back(s.first);
    for (const std::string& scene : scaling_scenes)
      for (const Config& c : trace_configs()) {
        const accel::StructureInfo* info = accel::find_structure(c.name);
        if ((c.label != c.name && c.label != "kdtree_sah") || info->selector || !applies(c.name, true)) continue;
        const std::string build = "Scaling/" + scene + "/build/" + c.label;
        timed_ms(benchmark::RegisterBenchmark(build.c_str(), bm_build_default, scene, c.name, c.knobs));
        for (RaySet set : {RaySet::Coherent, RaySet::Incoherent}) {
          const std::string bm = "Scaling/" + scene + "/" + ray_set_name(set) + "/" + c.label;
          timed_ms(benchmark::RegisterBenchmark(bm.c_str(), bm_trace, scene, set, c.name, c.knobs));
        }
      }
  }
  // Build time over the tree knobs; the BVH's target is <= 5 ms at (64, 4) for spheres8000.
  for (const Config& c : tree_configs()) {
    const std::string bm = "Build/spheres8000/" + c.label;
    timed_ms(benchmark::RegisterBenchmark(bm.c_str(), bm_build, std::string("spheres8000"), c.name, c.knobs)
        ->ArgNames({"max_depth", "max_leaf_size"})
        ->ArgsProduct({{8, 16, 20, 64}, {1, 2, 4, 8, 16}})
        );
  }
}

}  // namespace

int main(int argc, char** argv) {
  return bench::run_validated_benchmarks(argc, argv, register_benchmarks, g_validation_failures,
                                         "bench_trace: %d structure(s) failed validation against naive\n");
}
