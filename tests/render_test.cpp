// The render loop: image size, determinism at any thread count, the camera's film mapping, and
// the SPD and Whitted renders' shadow-ray packets against single rays.

#include "tracer/camera.h"
#include "tracer/parallel.h"
#include "tracer/render.h"
#include "tracer/render_frame.h"

#include "scenes_gen/generators.h"
#include "structure_configs.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

namespace {

using tracer::Vec3;

tracer::RenderResult render_with(const tracer::Scene& scene, const test_support::StructureConfig& structure,
                                 int threads, int w = 0, int h = 0, bool count = false,
                                 const tracer::Integrator& integrator = tracer::whitted_integrator()) {
  const accel::AnyAccel accel = structure.build(scene.geometry.primitive_bounds());
  tracer::RenderOptions options;
  options.threads = threads;
  options.width = w;
  options.height = h;
  options.count_traversal = count;
  return tracer::render(scene, accel, options, integrator);
}

TEST(Render, BitIdenticalAtAnyThreadCountWithJitteredSamples) {
  scenes_gen::GenOptions gen;
  tracer::Scene scene = scenes_gen::generate("refraction", gen);
  scene.camera.samples_per_pixel = 3;  // not a square: exercises the stratification remainder
  const tracer::RenderResult one = render_with(scene, "naive", 1, 61, 37);
  EXPECT_EQ(one.image.width(), 61);
  EXPECT_EQ(one.image.height(), 37);
  EXPECT_EQ(one.rays.eye, 61u * 37u * 3u);
  for (int threads : {2, 3, 8}) {
    const tracer::RenderResult many = render_with(scene, "naive", threads, 61, 37);
    EXPECT_EQ(many.image.content_hash(), one.image.content_hash()) << threads << " threads";
    EXPECT_TRUE(many.rays == one.rays);
  }
}

TEST(Render, CountingPassGivesTheSameImageAndCountsEveryQuery) {
  scenes_gen::GenOptions gen;
  const tracer::Scene scene = scenes_gen::generate("five", gen);
  const tracer::RenderResult timed = render_with(scene, "naive", 2, 32, 24);
  const tracer::RenderResult counted = render_with(scene, "naive", 2, 32, 24, true);
  EXPECT_EQ(timed.image.content_hash(), counted.image.content_hash());
  EXPECT_EQ(timed.traversal.rays, 0u);
  // Every closest-hit and any-hit query goes through the structure once.
  EXPECT_EQ(counted.traversal.rays, counted.rays.total());
  EXPECT_EQ(counted.traversal.prims_tested > 0, true);
}

// The SPD and Whitted renders shade each 4x4 packet of camera hits together and send their
// shadow rays as packets; the counting pass traces every ray alone. Both must give the same image
// and the same ray counts, through structures with and without a packet any-hit traversal, with
// and without SIMD sphere leaves (sphereflake is spheres only).
TEST(Render, ShadowPacketsGiveTheSingleRayImage) {
  scenes_gen::GenOptions gen;
  for (const tracer::Integrator* integrator : {&tracer::spd_integrator(), &tracer::whitted_integrator()})
    for (const char* kind : {"refraction", "sphereflake"}) {
      const tracer::Scene scene = scenes_gen::generate(kind, gen);
      for (const test_support::StructureConfig& accel : test_support::structures_at_every_isa()) {
        const tracer::RenderResult packets = render_with(scene, accel, 2, 45, 33, false, *integrator);
        const tracer::RenderResult single = render_with(scene, accel, 2, 45, 33, true, *integrator);
        EXPECT_EQ(packets.image.content_hash(), single.image.content_hash()) << kind << " " << accel.label();
        EXPECT_TRUE(packets.rays == single.rays) << kind << " " << accel.label();
        EXPECT_GT(single.rays.shadow, 300u) << kind;
      }
    }
}

TEST(Render, RejectsBadOptions) {
  scenes_gen::GenOptions gen;
  const tracer::Scene scene = scenes_gen::generate("five", gen);
  EXPECT_THROW(render_with(scene, "naive", -1), std::invalid_argument);
  EXPECT_THROW(render_with(scene, "naive", 1, -5, 10), std::invalid_argument);
}

TEST(ParallelItems, RunsEveryItemOnceOnItsWorkers) {
  for (int threads : {1, 2, 7}) {
    std::vector<int> runs(100, 0), worker_of(100, -1);
    tracer::parallel_items(threads, 100, [&](int worker, int item) {
      runs[std::size_t(item)]++;  // each item has one writer
      worker_of[std::size_t(item)] = worker;
    });
    for (int i = 0; i < 100; ++i) {
      EXPECT_EQ(runs[std::size_t(i)], 1) << i;
      EXPECT_TRUE(worker_of[std::size_t(i)] >= 0 && worker_of[std::size_t(i)] < threads);
    }
  }
  tracer::parallel_items(4, 0, [](int, int) { FAIL() << "no item to run"; });
}

TEST(ParallelItems, AWorkerExceptionStopsTheOthersAndReachesTheCaller) {
  for (int threads : {1, 3}) {
    std::atomic<int> after{0};
    EXPECT_THROW(tracer::parallel_items(threads, 100000,
                                        [&](int, int item) {
                                          if (item == 10) throw std::runtime_error("item 10");
                                          if (item > 10 + 64) {
                                            after++;
                                            // About a microsecond of work, so that running
                                            // every item would take 0.1 s on 1 core.
                                            const auto until = std::chrono::steady_clock::now() +
                                                               std::chrono::microseconds(1);
                                            while (std::chrono::steady_clock::now() < until) {
                                            }
                                          }
                                        }),
                 std::runtime_error);
    // Once item 10 has thrown, the others take no new item. Some run while the thrower is off
    // its core (on 2 busy cores, over 1,000 of the fast items once), but never most of them.
    EXPECT_LT(after.load(), 50000) << threads;
  }
}

/// For workers 1 .. threads-1 of one parallel_items call over `threads` items: how many such
/// calls their thread has served, itself included (each item waits until every worker has taken
/// one, so every worker takes part). A fresh thread answers 1.
std::vector<int> helper_calls(int threads) {
  thread_local int served = 0;
  std::vector<int> calls(static_cast<std::size_t>(threads));
  std::atomic<int> arrived{0};
  tracer::parallel_items(threads, threads, [&](int worker, int) {
    calls[std::size_t(worker)] = ++served;
    arrived++;
    while (arrived.load() < threads) std::this_thread::yield();
  });
  return {calls.begin() + 1, calls.end()};
}

TEST(ParallelItems, ReusesItsHelperThreadsAcrossCalls) {
  tracer::prepare_threads(3);
  const std::vector<int> first = helper_calls(3);
  const std::vector<int> second = helper_calls(3);
  ASSERT_EQ(second.size(), 2u);
  for (std::size_t i = 0; i < second.size(); ++i) EXPECT_EQ(second[i], first[i] + 1) << i;
  EXPECT_EQ(helper_calls(2)[0], first[0] + 2);  // a smaller job takes the first helper
}

TEST(ParallelItems, ANestedCallRunsOnThreadsOfItsOwn) {
  std::vector<int> runs(4 * 50, 0);
  tracer::parallel_items(2, 4, [&](int, int outer) {
    tracer::parallel_items(3, 50, [&](int, int inner) { runs[std::size_t(outer * 50 + inner)]++; });
  });
  for (std::size_t i = 0; i < runs.size(); ++i) EXPECT_EQ(runs[i], 1) << i;
}

/// A test integrator, one file's worth: red where the camera ray hits; with its knob "fail", an
/// exception on every camera ray through the right half of the image.
template <class Isect>
struct RedTracer {
  Isect isect;
  bool fail;
  tracer::Color trace_eye(const tracer::Ray& ray, tracer::RayCounts& counts) const {
    counts.eye++;
    if (fail && ray.dir.x > 0.0f) throw std::runtime_error("worker failed");
    return isect.closest(ray).found() ? tracer::Color(1, 0, 0) : tracer::Color(0.0f);
  }
};

struct RedParams {
  bool fail = false;  ///< Throw from a worker thread.
  static const knobs::KnobTable<RedParams>& knobs() {
    static const knobs::KnobTable<RedParams> t(
        "red", {knobs::Knob<RedParams>::boolean("fail", &RedParams::fail, "Throw from a worker thread.")});
    return t;
  }
};

const knobs::AnyKnobTable& red_knobs() { return RedParams::knobs(); }

tracer::RenderResult render_red(const tracer::Scene& scene, const accel::AnyAccel& accel,
                                const tracer::RenderOptions& options, const nlohmann::json& p) {
  const bool fail = p.get<RedParams>().fail;
  return tracer::render_frame(scene, accel, options, tracer::FilmSampling::PixelSamples,
                              [&](const auto& isect) {
                                return RedTracer<std::decay_t<decltype(isect)>>{isect, fail};
                              });
}

constexpr tracer::Integrator kRed{"red", "test: red where the camera ray hits", red_knobs,
                                  render_red};

TEST(Render, AnIntegratorIsOneFunctionThroughTheSameLoop) {
  scenes_gen::GenOptions gen;
  const tracer::Scene scene = scenes_gen::generate("five", gen);
  const auto boxes = scene.geometry.primitive_bounds();
  const accel::AnyAccel a = accel::make_accel("bvh", nlohmann::json::object(), boxes);
  tracer::RenderOptions options;
  options.width = 40;
  options.height = 30;
  options.threads = 3;
  const tracer::RenderResult r = tracer::render(scene, a, options, kRed);
  EXPECT_EQ(r.rays.eye, 40u * 30u);
  EXPECT_GT(r.image.mean(), 0.0);
  // A worker's exception stops the render and reaches the caller, at any thread count.
  for (int threads : {1, 2, 3}) {
    options.threads = threads;
    EXPECT_THROW(tracer::render(scene, a, options, kRed, {{"fail", true}}), std::runtime_error);
  }
}

TEST(Render, WindowRendersThatPartOfTheFullImage) {
  scenes_gen::GenOptions gen;
  const tracer::Scene scene = scenes_gen::generate("five", gen);
  const auto boxes = scene.geometry.primitive_bounds();
  const accel::AnyAccel a = accel::make_accel("naive", nlohmann::json::object(), boxes);
  tracer::RenderOptions options;
  options.width = 32;
  options.height = 24;
  options.threads = 2;
  const tracer::RenderResult full = tracer::render(scene, a, options, tracer::whitted_integrator());
  options.window = {5, 7, 21, 13};
  const tracer::RenderResult part = tracer::render(scene, a, options, tracer::whitted_integrator());
  ASSERT_EQ(part.image.width(), 16);
  ASSERT_EQ(part.image.height(), 6);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 16; ++x) EXPECT_EQ(part.image.at(x, y), full.image.at(x + 5, y + 7));
  options.window = {5, 7, 40, 13};
  EXPECT_THROW(tracer::render(scene, a, options, tracer::whitted_integrator()),
               std::invalid_argument);
  EXPECT_THROW(tracer::render(scene, a, {}, tracer::whitted_integrator(), {{"no_such_knob", 3}}),
               knobs::ConfigError);
}

TEST(Render, SampleOffsetsAreUniformOverThePixelForEverySampleCount) {
  // One sample per stratum of equal strata: over many pixels, the mean offset is the pixel's
  // centre and each half of the pixel gets half the samples, for square and non-square counts
  // alike (8 samples on a 3 x 3 grid left the bottom third short: a biased pixel estimate).
  for (int spp = 2; spp <= 40; ++spp) {
    double sum_x = 0.0, sum_y = 0.0;
    int top = 0, count = 0;
    for (int p = 0; p < 1000; ++p)
      for (int s = 0; s < spp; ++s) {
        float jx = 0, jy = 0;
        tracer::sample_offset(p % 17, p / 17, s, spp, jx, jy);
        sum_x += jx;
        sum_y += jy;
        top += jy < 0.5f;
        ++count;
      }
    EXPECT_NEAR(sum_x / count, 0.5, 0.02) << spp << " spp";
    EXPECT_NEAR(sum_y / count, 0.5, 0.02) << spp << " spp";
    EXPECT_NEAR(double(top) / count, 0.5, 0.03) << spp << " spp";
  }
}

TEST(Render, SampleOffsetsAreStratifiedAndStable) {
  for (int spp : {1, 2, 4, 5, 9}) {
    int per_half[2] = {0, 0};
    for (int s = 0; s < spp; ++s) {
      float jx = -1, jy = -1, jx2 = -1, jy2 = -1;
      tracer::sample_offset(7, 11, s, spp, jx, jy);
      tracer::sample_offset(7, 11, s, spp, jx2, jy2);
      EXPECT_EQ(jx, jx2);
      EXPECT_EQ(jy, jy2);
      ASSERT_TRUE(jx >= 0.0f && jx < 1.0f && jy >= 0.0f && jy < 1.0f);
      per_half[jx < 0.5f ? 0 : 1]++;
    }
    if (spp == 1) {
      EXPECT_EQ(per_half[1], 1);  // the centre, 0.5, counts as the right half
    } else if (spp == 4) {
      EXPECT_EQ(per_half[0], 2);
    }
  }
}

TEST(Camera, FilmCornersAndCentre) {
  tracer::Camera c;
  c.position = {0.0f, 0.0f, 0.0f};
  c.look_at = {0.0f, 0.0f, -1.0f};
  c.up = {0.0f, 1.0f, 0.3f};  // not perpendicular to the view: only its plane matters
  c.vfov_deg = 90.0f;
  const tracer::PinholeCamera cam(c, 200, 100);
  const Vec3 centre = cam.ray_through(100.0f, 50.0f).dir;
  EXPECT_NEAR(centre.x, 0.0f, 1e-6f);
  EXPECT_NEAR(centre.y, 0.0f, 1e-6f);
  EXPECT_NEAR(centre.z, -1.0f, 1e-6f);
  // Top-left corner: up 45 degrees, left by the aspect ratio 2.
  const Vec3 tl = cam.ray_through(0.0f, 0.0f).dir;
  EXPECT_NEAR(tl.x / -tl.z, -2.0f, 1e-5f);
  EXPECT_NEAR(tl.y / -tl.z, 1.0f, 1e-5f);
  const Vec3 br = cam.ray_through(200.0f, 100.0f).dir;
  EXPECT_NEAR(br.x / -br.z, 2.0f, 1e-5f);
  EXPECT_NEAR(br.y / -br.z, -1.0f, 1e-5f);
  EXPECT_NEAR(glm::length(br), 1.0f, 1e-6f);
  // Pixel (x, y) at offset (0.5, 0.5) is the film point (x + 0.5, y + 0.5).
  EXPECT_EQ(cam.primary_ray(3, 4).dir, cam.ray_through(3.5f, 4.5f).dir);
}

TEST(Camera, HitherClipsAlongTheViewDirection) {
  tracer::Camera c;
  c.hither = 2.0f;
  const tracer::PinholeCamera cam(c, 10, 10);
  const tracer::Ray r = cam.ray_through(0.0f, 0.0f);
  EXPECT_NEAR(glm::dot(r.tmin * r.dir, cam.forward()), 2.0f, 1e-5f);
}

// NFF/SPD worlds are left-handed: the same view then puts world +x on the other side of the
// film: each film point's ray is the right-handed one mirrored in x, with up and view unchanged.
TEST(Camera, LeftHandedMirrorsTheFilm) {
  tracer::Camera c;
  c.position = {0.0f, 0.0f, 0.0f};
  c.look_at = {0.0f, 0.0f, 1.0f};
  c.vfov_deg = 60.0f;
  tracer::Camera lh = c;
  lh.left_handed = true;
  const tracer::PinholeCamera right_handed(c, 64, 32), left_handed(lh, 64, 32);
  // Looking down +z with +y up, the left-handed image's right is world +x.
  EXPECT_GT(left_handed.ray_through(64.0f, 16.0f).dir.x, 0.0f);
  EXPECT_LT(right_handed.ray_through(64.0f, 16.0f).dir.x, 0.0f);
  for (float px : {0.0f, 10.5f, 32.0f, 63.0f}) {
    for (float py : {0.0f, 7.25f, 31.0f}) {
      const Vec3 a = right_handed.ray_through(px, py).dir;
      const Vec3 b = left_handed.ray_through(px, py).dir;
      EXPECT_NEAR(a.x, -b.x, 1e-6f);
      EXPECT_NEAR(a.y, b.y, 1e-6f);
      EXPECT_NEAR(a.z, b.z, 1e-6f);
    }
  }
}

}  // namespace
