// The Embree adapter: built only with Embree 3 (ACCELBENCH_HAVE_EMBREE); without it the factory
// must refuse `embree` with a clear message.

#include "accel/accel.h"
#include "accel/isa.h"
#include "tracer/sphere.h"

#include <gtest/gtest.h>

#include <algorithm>
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
      } catch (const accel::ConfigError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("parameter 'isa' = " + name), std::string::npos) << what;
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
  } catch (const accel::ConfigError& e) {
    EXPECT_STREQ(e.what(),
                 "embree: parameter 'isa' = avx512 needs AVX-512 F, CD, DQ, BW and VL, which this CPU lacks "
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
    accel::make_accel("embree", nullptr, sp.boxes, accel::BuildLimits{4096});
    FAIL() << "expected ConfigError";
  } catch (const accel::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--max-memory"), std::string::npos) << e.what();
  }
}

#else

TEST(Embree, NotBuiltSaysHowToGetIt) {
  try {
    accel::make_accel("embree", nullptr, std::span<const Aabb>{});
    FAIL() << "expected ConfigError";
  } catch (const accel::ConfigError& e) {
    EXPECT_STREQ(e.what(), "embree: not built (Embree 3 was not found; run scripts/setup)");
  }
  EXPECT_FALSE(accel::accel_built("embree"));
}

#endif

}  // namespace
