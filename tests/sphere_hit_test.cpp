// The SIMD sphere test (accel/sphere_hit.h) equals the scalar routine bit for bit, lane by lane,
// on every batch width this build has, over rays and spheres at extreme scales: far spheres,
// grazing rays, origins on and inside the surface, zero radii, +-0 direction components,
// unnormalised directions and tmin at a root. The build forbids FMA contraction; this test is
// what fails if the scalar routine and the lanes stop performing the same operations.

#include "accel/simd.h"
#include "accel/sphere_hit.h"
#include "accel/sphere_soa.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace {

using accel::Ray;
using accel::SphereShape;
using accel::Vec3;

struct Case {
  Ray ray;
  SphereShape sphere;
};

std::vector<Case> adversarial_cases(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), e(-6.0f, 6.0f);
  auto scale = [&] { return std::pow(10.0f, e(rng)); };
  auto dir = [&] {
    Vec3 d(u(rng), u(rng), u(rng));
    if (rng() % 5 == 0) d[rng() % 3] = (rng() & 1) ? 0.0f : -0.0f;
    return d * scale();
  };
  std::vector<Case> out;
  for (int i = 0; i < 20000; ++i) {
    Case c;
    const float s = scale();
    c.sphere.center = Vec3(u(rng), u(rng), u(rng)) * s;
    c.sphere.radius = (rng() % 17 == 0) ? 0.0f : std::abs(u(rng)) * s * std::pow(10.0f, -3.0f * std::abs(u(rng)));
    c.ray.dir = dir();
    switch (rng() % 5) {
      case 0:  // aimed at the sphere from far away
        c.ray.org = c.sphere.center - c.ray.dir * scale();
        break;
      case 1:  // grazing: aimed at a point on the silhouette
        c.ray.org = c.sphere.center + Vec3(c.sphere.radius, 0.0f, 0.0f) - c.ray.dir * scale();
        break;
      case 2:  // inside or at the centre
        c.ray.org = c.sphere.center + Vec3(u(rng), u(rng), u(rng)) * c.sphere.radius * 0.5f;
        if (rng() % 4 == 0) c.ray.org = c.sphere.center;
        break;
      case 3:  // on the surface
        c.ray.org = c.sphere.center + glm::normalize(Vec3(u(rng), u(rng), u(rng)) + Vec3(1e-3f)) * c.sphere.radius;
        break;
      default:  // anywhere
        c.ray.org = Vec3(u(rng), u(rng), u(rng)) * scale();
    }
    c.ray.tmin = (rng() % 3 == 0) ? std::abs(u(rng)) * scale() : 0.0f;
    out.push_back(c);
    if (rng() % 4 == 0) {  // tmin exactly at the scalar root
      const float t = accel::intersect_sphere(c.sphere.center, c.sphere.radius, c.ray);
      if (std::isfinite(t)) {
        c.ray.tmin = t;
        out.push_back(c);
      }
    }
  }
  return out;
}

template <class Batch>
void lanes_equal_scalar() {
  constexpr std::size_t L = Batch::size;
  const std::vector<Case> cases = adversarial_cases(std::uint32_t(L));
  std::size_t hits = 0, bad = 0;
  for (const Case& c : cases) {
    // One ray against L spheres: this case's sphere in every lane but one, the others' spheres
    // rotated in, so each lane position sees each kind of sphere.
    alignas(64) float cx[L], cy[L], cz[L], r[L], t[L];
    for (std::size_t i = 0; i < L; ++i) {
      const SphereShape& s = cases[(&c - cases.data() + i * 7919) % cases.size()].sphere;
      cx[i] = s.center.x;
      cy[i] = s.center.y;
      cz[i] = s.center.z;
      r[i] = s.radius;
    }
    const Batch tb = accel::intersect_spheres(Batch::load_aligned(cx), Batch::load_aligned(cy),
                                              Batch::load_aligned(cz), Batch::load_aligned(r), c.ray);
    tb.store_aligned(t);
    for (std::size_t i = 0; i < L; ++i) {
      const float want = accel::intersect_sphere(Vec3(cx[i], cy[i], cz[i]), r[i], c.ray);
      hits += std::isfinite(want);
      if (std::bit_cast<std::uint32_t>(want) != std::bit_cast<std::uint32_t>(t[i]) && ++bad <= 5)
        ADD_FAILURE() << "lane " << i << " of " << L << ": simd " << t[i] << " scalar " << want << " (org "
                      << c.ray.org.x << " " << c.ray.org.y << " " << c.ray.org.z << ", r " << r[i] << ")";
    }
  }
  EXPECT_EQ(bad, 0u);
  EXPECT_GT(hits, cases.size() / 20) << "the cases should hit often enough to test the roots";
}

TEST(SphereHit, FourLanesEqualTheScalarRoutine) { lanes_equal_scalar<accel::simd::Float4>(); }
TEST(SphereHit, LeafLanesEqualTheScalarRoutine) { lanes_equal_scalar<accel::simd::FloatLeaf>(); }
TEST(SphereHit, NativeWidthEqualsTheScalarRoutine) { lanes_equal_scalar<xsimd::batch<float>>(); }

TEST(SphereHit, MaskBitsNameTheTrueLanes) {
  using B = accel::simd::FloatLeaf;
  alignas(64) float v[B::size];
  for (std::size_t i = 0; i < B::size; ++i) v[i] = float(i % 3);
  const B b = B::load_aligned(v);
  std::uint32_t want = 0;
  for (std::size_t i = 0; i < B::size; ++i) want |= std::uint32_t(i % 3 == 1) << i;
  EXPECT_EQ(accel::simd::mask_bits<B>(b == B(1.0f)), want);
}

/// A leaf function that records what the SoA leaf hands it, like the tracer's closest hit.
struct Recorder {
  std::vector<std::pair<std::uint32_t, float>> accepted;
  bool accept(std::uint32_t id, float t, Ray& ray) {
    accepted.emplace_back(id, t);
    if (t < ray.tmax) {
      ray.tmax = t;
      return true;
    }
    return false;
  }
  bool operator()(std::uint32_t, Ray&) { return false; }
};

TEST(SphereSoA, LeavesOfAnyLengthGiveTheScalarHitsInIdOrder) {
  // Leaves of 1 to 17 spheres (past two batches of eight at AVX2), over a shuffled id array, the
  // last leaf ending the rows.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<accel::LeafRange> leaves;
  for (std::uint32_t count = 1, first = 0; count <= 17; first += count, ++count) leaves.push_back({first, count});
  std::vector<SphereShape> spheres(leaves.back().first + leaves.back().count);
  for (auto& s : spheres) s = {Vec3(u(rng), u(rng), 5.0f + u(rng)), 0.3f + 0.2f * u(rng)};
  std::vector<std::uint32_t> ids(spheres.size());
  for (std::uint32_t i = 0; i < ids.size(); ++i) ids[i] = (i * 11) % std::uint32_t(ids.size());
  accel::SphereSoA soa;
  soa.build(ids, leaves, spheres);
  for (const auto& [begin, count] : leaves)
    for (int pass = 0; pass < 3; ++pass) {
      Ray ray;
      ray.dir = Vec3(0.01f * u(rng), 0.01f * u(rng), 1.0f);
      Recorder rec;
      bool hit = false;
      accel::TraversalCounters counters;
      soa.test<true, false>(ids.data(), begin, count, ray, rec, &counters, hit);
      EXPECT_EQ(counters.prims_tested, count);
      // The scalar loop over the same ids, with the same acceptance.
      Ray scalar;
      scalar.dir = ray.dir;
      std::vector<std::pair<std::uint32_t, float>> want;
      for (std::uint32_t j = begin; j < begin + count; ++j) {
        const SphereShape& s = spheres[ids[j]];
        const float t = accel::intersect_sphere(s.center, s.radius, scalar);
        if (t <= scalar.tmax && std::isfinite(t)) want.emplace_back(ids[j], t);
        if (t < scalar.tmax) scalar.tmax = t;
      }
      EXPECT_EQ(std::bit_cast<std::uint32_t>(ray.tmax), std::bit_cast<std::uint32_t>(scalar.tmax));
      // Every sphere the scalar loop would accept is handed over, in id-array order.
      std::size_t k = 0;
      for (const auto& a : rec.accepted)
        if (k < want.size() && a == want[k]) ++k;
      EXPECT_EQ(k, want.size());
    }
}

}  // namespace
