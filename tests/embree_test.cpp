// The Embree adapter: built only with Embree 3 (ACCELBENCH_HAVE_EMBREE); without it the factory
// must refuse `embree` with a clear message.

#include "accel/accel.h"
#include "accel/isa.h"
#include "scenes_gen/generators.h"
#include "tracer/build_accel.h"
#include "tracer/camera.h"
#include "tracer/intersector.h"
#include "tracer/image_compare.h"
#include "tracer/offset_ray.h"
#include "tracer/render.h"
#include "tracer/sphere.h"
#include "tracer/surface.h"
#include "peer_point.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <cstdio>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace {

using accel::Aabb;
using accel::Ray;
using accel::Vec3;

#if ACCELBENCH_HAVE_EMBREE

struct Spheres {
  std::vector<Vec3> centres;
  std::vector<float> radii;
  std::vector<Aabb> boxes;
};

Spheres random_spheres(int n, std::uint32_t seed) {
  Spheres s;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f), r(0.1f, 0.4f);
  for (int i = 0; i < n; ++i) {
    s.centres.emplace_back(u(rng), u(rng), u(rng));
    s.radii.push_back(r(rng));
    s.boxes.push_back({s.centres.back() - Vec3(s.radii.back()), s.centres.back() + Vec3(s.radii.back())});
  }
  return s;
}

/// Closest hit (t, id) through a structure, with the lower id winning exact ties.
template <class S>
std::pair<float, std::uint32_t> closest(const S& s, const Spheres& sp, Ray ray,
                                        accel::TraversalCounters* c = nullptr) {
  std::uint32_t best = ~0u;
  auto leaf = [&](std::uint32_t id, Ray& r) {
    const float t = tracer::intersect_sphere(sp.centres[id], sp.radii[id], r);
    if (t < r.tmax || (t == r.tmax && t < accel::kInfinity && id < best)) {
      r.tmax = t;
      best = id;
      return true;
    }
    return false;
  };
  if (c)
    s.template intersect<true>(ray, leaf, c);
  else
    s.intersect(ray, leaf);
  return {ray.tmax, best};
}

TEST(Embree, ClosestAndAnyHitEqualNaive) {
  const Spheres sp = random_spheres(400, 11);
  const accel::Naive naive(sp.boxes);
  const accel::EmbreeAccel embree(sp.boxes, accel::EmbreeParams{}, accel::BuildLimits{});
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    Ray ray;
    ray.org = Vec3(u(rng), u(rng), u(rng)) * 8.0f;
    ray.dir = Vec3(u(rng), u(rng), u(rng)) * 5.0f - ray.org;
    if (i % 3 == 0) ray.tmax = 4.0f;
    const auto want = closest(naive, sp, ray);
    const auto got = closest(embree, sp, ray);
    ASSERT_EQ(got.second, want.second) << "ray " << i;
    ASSERT_EQ(got.first, want.first) << "ray " << i;
    hits += want.second != ~0u;
    auto any = [&](std::uint32_t id, Ray& r) {
      return tracer::intersect_sphere(sp.centres[id], sp.radii[id], r) < r.tmax;
    };
    ASSERT_EQ(embree.occluded(ray, any), naive.occluded(ray, any)) << "ray " << i;
  }
  EXPECT_GT(hits, 200);
}

TEST(Embree, CountsLeafCallsAndSaysWhatItCannotCount) {
  const Spheres sp = random_spheres(200, 13);
  const accel::AnyAccel any = accel::make_accel("embree", nullptr, sp.boxes);
  const auto& embree = std::get<accel::EmbreeAccel>(any);
  accel::TraversalCounters c;
  Ray ray;
  ray.org = Vec3(0.0f, 0.0f, -20.0f);
  ray.dir = sp.centres[0] - ray.org;
  EXPECT_EQ(closest(embree, sp, ray, &c).first, closest(accel::Naive(sp.boxes), sp, ray).first);
  EXPECT_EQ(c.rays, 1u);
  EXPECT_GT(c.prims_tested, 0u);
  EXPECT_LT(c.prims_tested, 200u);
  EXPECT_EQ(c.nodes_visited, 0u);
  const nlohmann::json stats = accel::stats_json_of(any);
  EXPECT_NE(stats.at("note").get<std::string>().find("nodes_visited"), std::string::npos);
  EXPECT_EQ(stats.at("primitives"), 200);
  EXPECT_GT(stats.at("memory_bytes").get<std::uint64_t>(), 0u);
}

TEST(Embree, MovesKeepTheSceneAlive) {
  const Spheres sp = random_spheres(100, 14);
  accel::EmbreeAccel a(sp.boxes, accel::EmbreeParams{}, accel::BuildLimits{});
  Ray ray;
  ray.org = Vec3(0.0f, 0.0f, -20.0f);
  const auto before = closest(a, sp, ray);
  accel::EmbreeAccel b(std::move(a));
  accel::EmbreeAccel c(random_spheres(10, 15).boxes, accel::EmbreeParams{}, accel::BuildLimits{});
  c = std::move(b);
  EXPECT_EQ(closest(c, sp, ray), before);
  accel::AnyAccel any = std::move(c);
  EXPECT_EQ(accel::name_of(any), "embree");
}

TEST(Embree, KnobsRoundTripAndMediumQualityAgrees) {
  const Spheres sp = random_spheres(300, 16);
  const nlohmann::json knobs = {{"build_quality", "medium"}, {"robust", true}, {"build_threads", 2},
                                {"isa", "sse4.2"},          {"packet", "16"}};
  const accel::AnyAccel any = accel::make_accel("embree", knobs, sp.boxes);
  EXPECT_EQ(accel::params_of(any), knobs);
  const accel::Naive naive(sp.boxes);
  Ray ray;
  ray.org = Vec3(0.3f, -0.2f, -20.0f);
  EXPECT_EQ(closest(std::get<accel::EmbreeAccel>(any), sp, ray), closest(naive, sp, ray));
}

// Every level the CPU has builds and runs at that level, with Embree's native packet width; every
// other level is refused in one line naming the level and the knob. The oracle and image tests
// cover the levels the CPU has through the knob's probes and structures_at_every_isa().
TEST(Embree, RunsAtEveryIsaTheCpuHasAndRefusesTheOthers) {
  const Spheres sp = random_spheres(300, 18);
  const accel::IsaSet cpu = accel::cpu_isas();
  EXPECT_TRUE(cpu & accel::isa_bit(accel::build_isa())) << "this build targets more than the CPU has";
  int ran = 0;
  for (accel::Isa isa : accel::kIsas) {
    const std::string name = accel::isa_name(isa);
    if (cpu & accel::isa_bit(isa)) {
      const accel::AnyAccel any = accel::make_accel("embree", {{"isa", name}}, sp.boxes);
      const auto& embree = std::get<accel::EmbreeAccel>(any);
      EXPECT_EQ(embree.isa(), isa);
      EXPECT_EQ(embree.packet_lanes(), accel::isa_lanes(isa));
      Ray ray;
      ray.org = Vec3(0.1f, 0.2f, -20.0f);
      EXPECT_EQ(closest(embree, sp, ray), closest(accel::Naive(sp.boxes), sp, ray)) << name;
      ++ran;
    } else {
      try {
        accel::make_accel("embree", {{"isa", name}}, sp.boxes);
        ADD_FAILURE() << name << ": expected a refusal";
      } catch (const knobs::ConfigError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("knob 'isa' = " + name), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      }
    }
  }
  EXPECT_GE(ran, 2);  // every x86-64 CPU has sse2; this one has more
  // The oracle tries every level the knob knows.
  const accel::StructureInfo* info = accel::find_structure("embree");
  ASSERT_NE(info, nullptr);
  std::vector<std::string> probed;
  for (const nlohmann::json& k : info->knob_table)
    if (k.at("name") == "isa") probed = k.at("probes").get<std::vector<std::string>>();
  for (accel::Isa isa : accel::kIsas)
    EXPECT_NE(std::find(probed.begin(), probed.end(), accel::isa_name(isa)), probed.end()) << accel::isa_name(isa);
}

TEST(Embree, IsaRefusalNamesTheLevelAndTheKnob) {
  using accel::Isa;
  const accel::IsaSet avx2_cpu = accel::isa_bit(Isa::Sse2) | accel::isa_bit(Isa::Sse42) |
                                 accel::isa_bit(Isa::Avx) | accel::isa_bit(Isa::Avx2);
  try {
    accel::check_embree_isa(accel::EmbreeIsa::Avx512, avx2_cpu);
    FAIL() << "expected ConfigError";
  } catch (const knobs::ConfigError& e) {
    EXPECT_STREQ(e.what(),
                 "embree: knob 'isa' = avx512 needs AVX-512 F, CD, DQ, BW and VL, which this CPU lacks "
                 "(it has sse2, sse4.2, avx, avx2)");
  }
  EXPECT_NO_THROW(accel::check_embree_isa(accel::EmbreeIsa::Avx2, avx2_cpu));
  EXPECT_NO_THROW(accel::check_embree_isa(accel::EmbreeIsa::Cpu, avx2_cpu));
  EXPECT_EQ(accel::resolve_embree_isa(accel::EmbreeIsa::Cpu, avx2_cpu), Isa::Avx2);
  EXPECT_EQ(accel::resolve_embree_isa(accel::EmbreeIsa::Build, avx2_cpu), accel::build_isa());
  EXPECT_EQ(accel::resolve_embree_packet(accel::EmbreePacket::Auto, Isa::Avx512), 16);
  EXPECT_EQ(accel::resolve_embree_packet(accel::EmbreePacket::Auto, Isa::Avx2), 8);
  EXPECT_EQ(accel::resolve_embree_packet(accel::EmbreePacket::Auto, Isa::Sse42), 4);
  EXPECT_EQ(accel::resolve_embree_packet(accel::EmbreePacket::Lanes16, Isa::Sse2), 16);
  // `--knob packet=8` hands the knob the number 8; it is the choice "8".
  const Spheres sp = random_spheres(10, 19);
  const accel::AnyAccel any = accel::make_accel("embree", {{"packet", 8}}, sp.boxes);
  EXPECT_EQ(std::get<accel::EmbreeAccel>(any).packet_lanes(), 8);
  EXPECT_EQ(accel::params_of(any).at("packet"), "8");
}

TEST(Embree, MemoryBudgetIsHonoured) {
  const Spheres sp = random_spheres(5000, 17);
  try {
    accel::make_accel("embree", nullptr, sp.boxes, accel::BuildLimits{4096, {}});
    FAIL() << "expected ConfigError";
  } catch (const knobs::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--max-memory"), std::string::npos) << e.what();
  }
}

/// A peer with its own primitive routine (embree_points, embree_triangles) on the ray kinds a
/// render casts (camera rays, rays spawned off their hits, shadow rays) through `scene`, at every
/// ISA the CPU has, single rays and packets: the same primitive and t within 1e-5 relative for
/// >= 99.9% of rays, every hit point within 1e-5 of its coordinates' size, the same any-hit
/// answer for >= 99.9%. `reference` is naive, or on scenes too
/// large for naive a structure the oracle holds bit-identical to it.
void expect_peer_agrees_at_every_isa(const std::string& peer, const nlohmann::json& knobs, const tracer::Scene& scene,
                                     const std::string& reference) {
  const tracer::Geometry& g = scene.geometry;
  const std::vector<Aabb> boxes = g.primitive_bounds();
  const accel::AnyAccel ref = tracer::build_accel(reference, nullptr, g, boxes);
  const tracer::PinholeCamera camera(scene.camera, 240, 180);
  std::vector<Ray> rays, shadow;
  for (int y = 0; y < 180; ++y)
    for (int x = 0; x < 240; ++x) rays.push_back(camera.primary_ray(x, y));
  std::vector<tracer::Hit> want(rays.size());
  tracer::with_intersector<false>(g, ref, tracer::TriangleTest::Watertight, [&](const auto& isect) {
    for (std::size_t i = 0; i < rays.size(); ++i) want[i] = isect.closest(rays[i]);
  });
  std::mt19937 rng(20);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  const std::size_t camera_rays = rays.size();
  for (std::size_t i = 0; i < camera_rays; ++i) {
    if (!want[i].found()) continue;
    const tracer::SurfacePoint sp = tracer::surface_point(g, rays[i], want[i], tracer::TriangleTest::Watertight);
    Vec3 d = glm::normalize(Vec3(gauss(rng), gauss(rng), gauss(rng)));
    if (glm::dot(d, sp.n_geo) < 0.0f) d = -d;
    rays.push_back(tracer::spawn_ray(sp, d));
    for (const tracer::PointLight& light : scene.lights) shadow.push_back(tracer::spawn_ray_to(sp, light.position));
  }
  want.resize(rays.size());
  std::vector<bool> blocked(shadow.size());
  tracer::with_intersector<false>(g, ref, tracer::TriangleTest::Watertight, [&](const auto& isect) {
    for (std::size_t i = camera_rays; i < rays.size(); ++i) want[i] = isect.closest(rays[i]);
    for (std::size_t i = 0; i < shadow.size(); ++i) blocked[i] = isect.occluded(shadow[i]);
  });
  ASSERT_GT(rays.size(), camera_rays + 8000);
  ASSERT_GT(shadow.size(), 8000u);

  for (accel::Isa isa : accel::isas_in(accel::cpu_isas())) {
    nlohmann::json k = knobs;
    k["isa"] = accel::isa_name(isa);
    const std::string label = peer + " " + k.dump();
    SCOPED_TRACE(label);
    const accel::AnyAccel a = tracer::build_accel(peer, k, g, boxes);
    std::visit(
        [&](const auto& s) {
          if constexpr (requires { s.native(); }) {
            EXPECT_TRUE(s.native()) << "its own primitives answer";
          }
        },
        a.variant());
    std::vector<tracer::Hit> single(rays.size()), packets(rays.size());
    std::vector<bool> occluded(shadow.size()), occluded_packets(shadow.size());
    tracer::with_intersector<false>(g, a, tracer::TriangleTest::Watertight, [&](const auto& isect) {
      for (std::size_t i = 0; i < rays.size(); ++i) single[i] = isect.closest(rays[i]);
      for (std::size_t i = 0; i < rays.size(); i += 16) {
        const std::size_t n = std::min<std::size_t>(16, rays.size() - i);
        isect.closest_packet(std::span<const Ray>(rays.data() + i, n), std::span<tracer::Hit>(packets.data() + i, n));
      }
      for (std::size_t i = 0; i < shadow.size(); ++i) occluded[i] = isect.occluded(shadow[i]);
      for (std::size_t i = 0; i < shadow.size(); i += 16) {
        const std::size_t n = std::min<std::size_t>(16, shadow.size() - i);
        const std::uint32_t bits = isect.occluded_packet(std::span<const Ray>(shadow.data() + i, n));
        for (std::size_t lane = 0; lane < n; ++lane) occluded_packets[i + lane] = (bits >> lane) & 1u;
      }
    });
    for (const auto* got : {&single, &packets}) {
      // t relative to t, and the hit point's difference relative to the coordinates it is
      // computed from (max(|org|, t |dir|)): a short secondary ray's t carries an ulp of its
      // origin, which is a large part of a t near 0, and the same few ulps of the hit point.
      std::size_t other = 0, t_off = 0;
      double max_rel = 0.0, max_point = 0.0;
      for (std::size_t i = 0; i < rays.size(); ++i) {
        if ((*got)[i].prim != want[i].prim) {
          ++other;
        } else if (want[i].found()) {
          const double dt = std::abs(double((*got)[i].t) - double(want[i].t));
          const double rel = dt / double(want[i].t);
          max_rel = std::max(max_rel, rel);
          max_point = std::max(max_point, peer_point::offset(rays[i], (*got)[i].t, want[i].t));
          t_off += rel > 1e-5;
        }
      }
      const char* what = got == &single ? "single rays" : "packets";
      std::printf("%s, %s: %zu of %zu rays another primitive; t within 1e-5 relative on all but %zu, within %.2g on "
                  "all; hit points within %.2g of their coordinates\n",
                  label.c_str(), what, other, rays.size(), t_off, max_rel, max_point);
      EXPECT_LE(double(other), 0.001 * double(rays.size())) << what;
      EXPECT_LE(double(t_off), 0.001 * double(rays.size())) << what;
      EXPECT_LE(max_point, 1e-5) << what;
    }
    for (const auto* got : {&occluded, &occluded_packets}) {
      std::size_t other = 0;
      for (std::size_t i = 0; i < shadow.size(); ++i) other += (*got)[i] != blocked[i];
      std::printf("%s, %s: %zu of %zu shadow rays another answer\n", label.c_str(),
                  got == &occluded ? "single rays" : "packets", other, shadow.size());
      EXPECT_LE(double(other), 0.001 * double(shadow.size())) << (got == &occluded ? "single rays" : "packets");
    }
  }
}

TEST(EmbreePoints, AgreesWithNaiveWithinItsToleranceAtEveryIsa) {
  expect_peer_agrees_at_every_isa("embree_points", nlohmann::json::object(), scenes_gen::generate("spheres8000", {}),
                                  "naive");
}

// Embree's triangles, in its default, robust and high-quality builds, on the standard bunny (or, without
// the shared models, spheres8000 as 160,000 triangles), against bvh8 (bit-identical to naive on
// every mesh scene of the oracle; naive itself would take minutes here).
TEST(EmbreeTriangles, AgreesWithNaiveWithinItsToleranceAtEveryIsa) {
  scenes_gen::GenOptions o;
  tracer::Scene scene;
  if (std::filesystem::exists(std::filesystem::path(ACCELBENCH_MESHES_DIR) / "stanford-bunny.obj")) {
    o.model = "bunny";
    scene = scenes_gen::generate("mesh", o);
  } else {
    std::printf("%s is absent: spheres8000 as icospheres instead of the bunny\n", ACCELBENCH_MESHES_DIR);
    o.count = 0;
    scene = scenes_gen::generate("tessellated_spheres", o);
  }
  for (const nlohmann::json& knobs : {nlohmann::json{{"robust", false}}, nlohmann::json{{"robust", true}},
                                      nlohmann::json{{"build_quality", "high"}}})
    expect_peer_agrees_at_every_isa("embree_triangles", knobs, scene, "bvh8");
}

TEST(EmbreeTriangles, WithOtherPrimitivesItIsTheUserGeometryAdapter) {
  // spheres and triangles together: nothing native to attach, our routine through callbacks,
  // bit-identical to naive (the oracle's "mixed" scene checks it at length).
  tracer::Scene scene = scenes_gen::generate("spheres8000", {});
  tracer::Triangle tri;
  tri.p0 = {-1.0f, -1.0f, 0.0f};
  tri.p1 = {1.0f, -1.0f, 0.0f};
  tri.p2 = {0.0f, 1.0f, 0.0f};
  scene.geometry.triangles.push_back(tri);
  scene.geometry.finalize();
  const std::vector<Aabb> boxes = scene.geometry.primitive_bounds();
  const accel::AnyAccel a = tracer::build_accel("embree_triangles", nullptr, scene.geometry, boxes);
  EXPECT_FALSE(std::get<accel::EmbreeTriangles>(a).native());
  EXPECT_FALSE(accel::find_structure("embree_triangles")->exact);
  EXPECT_TRUE(accel::takes_triangles(a));
  EXPECT_TRUE(accel::takes_triangles(tracer::build_accel("bvh8", nullptr, scene.geometry, boxes)));  // SIMD leaves
  EXPECT_FALSE(accel::takes_triangles(tracer::build_accel("bvh", nullptr, scene.geometry, boxes)));
  EXPECT_FALSE(accel::takes_triangles(tracer::build_accel("embree_points", nullptr, scene.geometry, boxes)));
  EXPECT_EQ(accel::find_structure("embree_triangles")->native_shapes, "triangles");
  EXPECT_EQ(accel::find_structure("embree_points")->native_shapes, "spheres");
  EXPECT_EQ(accel::find_structure("bvh8")->native_shapes, "");
  EXPECT_EQ(accel::params_of(a).at("robust"), false) << "Embree's own defaults are the defaults";
  EXPECT_EQ(accel::params_of(a).at("build_quality"), "medium") << "Embree's own defaults are the defaults";
}

TEST(EmbreeTriangles, MemoryBudgetNamesIt) {
  scenes_gen::GenOptions o;
  o.count = 0;
  const tracer::Scene scene = scenes_gen::generate("tessellated_spheres", o);
  const std::vector<Aabb> boxes = scene.geometry.primitive_bounds();
  accel::BuildLimits limits;
  limits.max_memory_bytes = 4096;
  try {
    tracer::build_accel("embree_triangles", nullptr, scene.geometry, boxes, limits);
    FAIL() << "expected ConfigError";
  } catch (const knobs::ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("embree_triangles: ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("--max-memory"), std::string::npos) << e.what();
  }
}

// Its Whitted render of spheres8000 stays within bench_trace's image tolerance (2% of pixels more
// than 1% off naive's): through glass and mirrors its t, a few ulps from ours, moves whole paths.
TEST(EmbreePoints, RendersWithinTheImageTolerance) {
  const tracer::Scene scene = scenes_gen::generate("spheres8000", {});
  const std::vector<Aabb> boxes = scene.geometry.primitive_bounds();
  tracer::RenderOptions o;
  o.threads = 2;
  o.width = 1024;
  o.height = 768;
  o.window = {512 - 48, 384 - 48, 512 + 48, 384 + 48};
  const tracer::RenderResult ref = tracer::render(scene, accel::make_accel("naive", {}, boxes), o, tracer::whitted_integrator());
  accel::AnyAccel points = accel::make_accel("embree_points", {}, boxes);
  tracer::attach_geometry(points, scene.geometry);
  const tracer::RenderResult got = tracer::render(scene, points, o, tracer::whitted_integrator());
  const tracer::ImageDifference d = tracer::compare_images(got.image, ref.image);
  std::printf("embree_points, spheres8000 centre window: %zu of %zu pixels more than 1%% off\n", d.pixels_off, d.pixels);
  EXPECT_LE(d.fraction_off, 0.02);
  EXPECT_GT(d.pixels, 9000u);
  EXPECT_NEAR(double(got.rays.total()), double(ref.rays.total()), 0.001 * double(ref.rays.total()));
}

TEST(EmbreePoints, WithoutItsSpheresItIsTheUserGeometryAdapter) {
  const Spheres sp = random_spheres(300, 21);
  const accel::AnyAccel any = accel::make_accel("embree_points", nullptr, sp.boxes);
  EXPECT_FALSE(std::get<accel::EmbreePoints>(any).native());
  const accel::Naive naive(sp.boxes);
  std::mt19937 rng(22);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 500; ++i) {
    Ray ray;
    ray.org = Vec3(u(rng), u(rng), u(rng)) * 8.0f;
    ray.dir = Vec3(u(rng), u(rng), u(rng));
    ASSERT_EQ(closest(std::get<accel::EmbreePoints>(any), sp, ray), closest(naive, sp, ray)) << i;
  }
  // Errors name it, not the adapter it is built on.
  try {
    accel::make_accel("embree_points", nullptr, random_spheres(5000, 23).boxes, accel::BuildLimits{4096, {}});
    FAIL() << "expected ConfigError";
  } catch (const knobs::ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("embree_points: ", 0), 0u) << e.what();
  }
  EXPECT_FALSE(accel::find_structure("embree_points")->exact);
  EXPECT_TRUE(accel::find_structure("embree")->exact);
}

#else

TEST(Embree, NotBuiltSaysHowToGetIt) {
  try {
    accel::make_accel("embree", nullptr, std::span<const Aabb>{});
    FAIL() << "expected ConfigError";
  } catch (const knobs::ConfigError& e) {
    EXPECT_STREQ(e.what(), "embree: not built (Embree 3 was not found; run scripts/setup)");
  }
  EXPECT_FALSE(accel::accel_built("embree"));
}

#endif

}  // namespace
