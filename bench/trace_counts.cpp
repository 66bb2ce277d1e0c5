// One structure's trace of one of bench_trace's ray sets, for counting under callgrind
// (scripts/count_trace): the instructions and the simulated cache misses of a trace do not move
// with the host's load the way its time does, so two builds, or two structures, can be compared
// on a shared host where timings of the same binary spread by 10-25%. They are not times: a
// change that saves instructions may still wait as long on memory; confirm a change that the
// counts favour with bench_trace or scripts/bench_embree on a quiet host.
//
// The rays are bench_trace's, at the same size: camera rays, rays spawned off their hits
// (incoherent), or shadow rays to the lights (any hit). Before counting, the structure's answers
// are checked on every ray against the binary BVH's, whose answers are checked against naive's on
// a sample, as bench_trace checks them (exact structures bit for bit; Embree's own primitives
// within its tolerance); a failed check exits 1. callgrind instruments the program from that check
// on (which warms its simulated caches, as bench_trace's check warms the real ones before timing)
// and counts the `--passes` traces after it and nothing else (its client requests, below; run it
// with --instr-atstart=no --collect-atstart=no).
//
//   build/bin/trace_counts --scene spheres8000 --accel bvh8 [--rays camera|incoherent|shadow]
//                          [--knobs JSON] [--resolution 1024x768] [--passes 1]
//   build/bin/trace_counts --build-isa     # the ISA the build targets: valgrind runs no AVX-512

#include "accel/accel.h"
#include "accel/isa.h"
#include "bench_rays.h"
#include "bench_scenes.h"
#include "bench_validation.h"
#include "tracer/build_accel.h"
#include "tracer/intersector.h"

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define ACCELBENCH_CALLGRIND 1
#else
#define ACCELBENCH_CALLGRIND 0
#define CALLGRIND_START_INSTRUMENTATION
#define CALLGRIND_STOP_INSTRUMENTATION
#define CALLGRIND_TOGGLE_COLLECT
#endif

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <map>
#include <string>
#include <vector>

namespace {

using accel::Ray;
using tracer::Hit;

enum class RaySet { Camera, Incoherent, Shadow };

void trace(const tracer::Geometry& g, const accel::AnyAccel& a, const std::vector<Ray>& rays, std::vector<Hit>& hits) {
  hits.resize(rays.size());
  tracer::with_intersector<false>(g, a, tracer::TriangleTest::Watertight, [&](const auto& isect) {
    for (std::size_t i = 0; i < rays.size(); ++i) hits[i] = isect.closest(rays[i]);
  });
}

void occlude(const tracer::Geometry& g, const accel::AnyAccel& a, const std::vector<Ray>& rays,
             std::vector<std::uint8_t>& blocked) {
  blocked.resize(rays.size());
  tracer::with_intersector<false>(g, a, tracer::TriangleTest::Watertight, [&](const auto& isect) {
    for (std::size_t i = 0; i < rays.size(); ++i) blocked[i] = isect.occluded(rays[i]);
  });
}

/// Traces `rays` through `a`: closest hits into `hits`, or any-hit answers into `blocked`.
void answer(const tracer::Geometry& g, const accel::AnyAccel& a, const std::vector<Ray>& rays, bool any_hit,
            std::vector<Hit>& hits, std::vector<std::uint8_t>& blocked) {
  if (any_hit)
    occlude(g, a, rays, blocked);
  else
    trace(g, a, rays, hits);
}

/// The binary BVH's answers on `rays` (the reference), checked against naive's on a sample of
/// about 10^8 primitive tests; exits 1 when they differ.
void reference(const tracer::Geometry& g, const std::vector<accel::Aabb>& boxes, const std::vector<Ray>& rays,
               bool any_hit, std::vector<Hit>& hits, std::vector<std::uint8_t>& blocked) {
  const accel::AnyAccel bvh = tracer::build_accel("bvh", nullptr, g, boxes);
  if (any_hit)
    occlude(g, bvh, rays, blocked);
  else
    trace(g, bvh, rays, hits);
  const std::size_t stride =
      std::max<std::size_t>(64, std::bit_ceil(std::size_t(double(boxes.size()) * double(rays.size()) / 1e8) + 1));
  std::vector<Ray> sample;
  for (std::size_t i = 0; i < rays.size(); i += stride) sample.push_back(rays[i]);
  const accel::AnyAccel naive = accel::make_accel("naive", nullptr, boxes);
  std::vector<Hit> naive_hits;
  std::vector<std::uint8_t> naive_blocked;
  if (any_hit)
    occlude(g, naive, sample, naive_blocked);
  else
    trace(g, naive, sample, naive_hits);
  std::size_t bad = 0;
  for (std::size_t k = 0; k < sample.size(); ++k) {
    const std::size_t i = k * stride;
    bad += any_hit ? naive_blocked[k] != blocked[i]
                   : naive_hits[k].prim != hits[i].prim ||
                         std::bit_cast<std::uint32_t>(naive_hits[k].t) != std::bit_cast<std::uint32_t>(hits[i].t);
  }
  if (bad) {
    std::fprintf(stderr, "trace_counts: the bvh reference differs from naive on %zu of %zu sampled rays\n", bad,
                 sample.size());
    std::exit(1);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene_name = "spheres8000", structure = "bvh8", knobs_text = "{}", resolution = "1024x768";
  RaySet set = RaySet::Camera;
  int passes = 1;
  CLI::App app{"One structure's trace of one of bench_trace's ray sets, checked, for counting under callgrind"};
  app.add_option("--scene", scene_name, "a generator's scene, random1M, bunny, ogre, nefertiti, grid1M or a scaling scene");
  app.add_option("--accel", structure, "the structure (accelbench list)");
  const std::map<std::string, RaySet> sets = {
      {"camera", RaySet::Camera}, {"incoherent", RaySet::Incoherent}, {"shadow", RaySet::Shadow}};
  app.add_option("--rays", set, "camera, incoherent or shadow")->transform(CLI::CheckedTransformer(sets));
  app.add_option("--knobs", knobs_text, "the structure's knobs as a JSON object, e.g. '{\"traversal_cost\": 3}'");
  app.add_option("--passes", passes, "traces of the rays counted")->check(CLI::Range(1, 1000));
  app.add_option("--resolution", resolution, "camera rays WIDTHxHEIGHT (bench_trace's: 1024x768)");
  bool print_isa = false;
  app.add_flag("--build-isa", print_isa, "print the ISA this build targets and exit (valgrind runs no AVX-512)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "trace_counts: %s\n", e.what());
    return 2;
  }
  if (print_isa) {
    std::printf("%s\n", accel::isa_name(accel::build_isa()));
    return 0;
  }
  int width = 0, height = 0;
  char tail = 0;
  if (std::sscanf(resolution.c_str(), "%dx%d%c", &width, &height, &tail) != 2 || width < 1 || height < 1 ||
      width > 16384 || height > 16384) {
    std::fprintf(stderr, "trace_counts: --resolution: expected WIDTHxHEIGHT, each 1-16384, got '%s'\n",
                 resolution.c_str());
    return 2;
  }
  try {
    const nlohmann::json knobs = nlohmann::json::parse(knobs_text, nullptr, false);
    if (!knobs.is_object()) {
      std::fprintf(stderr, "trace_counts: --knobs: not a JSON object: %s\n", knobs_text.c_str());
      return 2;
    }
    const tracer::Scene scene = bench::bench_scene(scene_name);
    const tracer::Geometry& g = scene.geometry;
    const std::vector<accel::Aabb> boxes = g.primitive_bounds();
    // The camera rays and the reference's hits, then the set spawned off them.
    std::vector<Ray> rays = bench::camera_rays(scene, width, height);
    std::vector<Hit> want;
    std::vector<std::uint8_t> want_blocked;
    const bool any_hit = set == RaySet::Shadow;
    reference(g, boxes, rays, false, want, want_blocked);
    if (set != RaySet::Camera) {
      rays = set == RaySet::Incoherent ? bench::spawned_rays(g, rays, want) : bench::shadow_rays(scene, rays, want);
      reference(g, boxes, rays, any_hit, want, want_blocked);
    }

    const accel::AnyAccel a = tracer::build_accel(structure, knobs, g, boxes);
    std::vector<Hit> hits;
    std::vector<std::uint8_t> blocked;
    CALLGRIND_START_INSTRUMENTATION;
    answer(g, a, rays, any_hit, hits, blocked);  // the check, on the path counted
    const bool exact = bench::is_exact(structure);
    const bench::Validation v =
        any_hit ? bench::blocked_mismatch(rays, blocked, want_blocked, exact,
                                          [&](const Ray& r) {
                                            std::vector<Hit> one;
                                            trace(g, a, {r}, one);
                                            return one[0].t;
                                          })
                : bench::hit_mismatch(g, rays, hits, want, exact);
    if (!v.why.empty()) {
      std::fprintf(stderr, "trace_counts: %s on %s failed its check against naive: %s\n", structure.c_str(),
                   scene_name.c_str(), v.why.c_str());
      return 1;
    }
    CALLGRIND_TOGGLE_COLLECT;
    for (int p = 0; p < passes; ++p) answer(g, a, rays, any_hit, hits, blocked);
    CALLGRIND_TOGGLE_COLLECT;
    CALLGRIND_STOP_INSTRUMENTATION;
    std::printf("rays %zu\npasses %d\ncallgrind_requests %s\n", rays.size(), passes,
                ACCELBENCH_CALLGRIND ? "yes" : "no");
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "trace_counts: %s\n", e.what());
    return 2;
  }
}
