#include "tracer/cone.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

using tracer::Cone;
using tracer::make_cone;
using tracer::Ray;
using tracer::Vec3;

Ray ray_of(Vec3 org, Vec3 dir, float tmin = 0.0f) {
  Ray r;
  r.org = org;
  r.dir = dir;
  r.tmin = tmin;
  return r;
}

const Cone kCylinder = make_cone(Vec3(0, 0, 0), 1.0f, Vec3(0, 0, 2), 1.0f);
const Cone kCone = make_cone(Vec3(0, 0, 0), 1.0f, Vec3(0, 0, 1), 0.5f);
const Cone kSharp = make_cone(Vec3(0, 0, 0), 1.0f, Vec3(0, 0, 2), 0.0f);

TEST(Cylinder, HitsFromOutsideAndInside) {
  EXPECT_FLOAT_EQ(intersect(kCylinder, ray_of({-5, 0, 1}, {1, 0, 0})), 4.0f);
  EXPECT_FLOAT_EQ(intersect(kCylinder, ray_of({0, 0, 1}, {1, 0, 0})), 1.0f);
  // Beyond the first root, the far wall.
  EXPECT_FLOAT_EQ(intersect(kCylinder, ray_of({-5, 0, 1}, {1, 0, 0}, 4.5f)), 6.0f);
  EXPECT_FALSE(std::isfinite(intersect(kCylinder, ray_of({-5, 0, 1}, {1, 0, 0}, 6.5f))));
  // Unnormalised directions: t in units of |dir|.
  EXPECT_FLOAT_EQ(intersect(kCylinder, ray_of({-5, 0, 1}, {2, 0, 0})), 2.0f);
}

TEST(Cylinder, NoEndCaps) {
  // Above and below the ends the infinite cylinder would be hit; the truncated one is not.
  EXPECT_FALSE(std::isfinite(intersect(kCylinder, ray_of({-5, 0, 2.5f}, {1, 0, 0}))));
  EXPECT_FALSE(std::isfinite(intersect(kCylinder, ray_of({-5, 0, -0.5f}, {1, 0, 0}))));
  // Through the open bottom onto the inner wall: x = 1 at parameter 1, z = 1.
  EXPECT_FLOAT_EQ(intersect(kCylinder, ray_of({0, 0, -1}, {1, 0, 2})), 1.0f);
}

TEST(Cylinder, RaysAlongTheAxis) {
  // On the axis, inside, and exactly in the surface: no cap, so never a hit, and never NaN.
  for (const Vec3 org : {Vec3(0, 0, -5), Vec3(0.5f, 0, -5), Vec3(1, 0, -5), Vec3(0, 0, 1)}) {
    const float t = intersect(kCylinder, ray_of(org, {0, 0, 1}));
    EXPECT_FALSE(std::isnan(t));
    EXPECT_FALSE(std::isfinite(t)) << org.x;
    EXPECT_FALSE(std::isfinite(intersect(kCylinder, ray_of(org, {0, 0, -1}))));
  }
}

TEST(Cylinder, GrazingRays) {
  // Tangent at (0, 1, 1): the double root.
  EXPECT_FLOAT_EQ(intersect(kCylinder, ray_of({-5, 1, 1}, {1, 0, 0})), 5.0f);
  // Just outside misses, just inside hits near the tangent point.
  EXPECT_FALSE(std::isfinite(intersect(kCylinder, ray_of({-5, 1.0001f, 1}, {1, 0, 0}))));
  const float t = intersect(kCylinder, ray_of({-5, 0.9999f, 1}, {1, 0, 0}));
  EXPECT_NEAR(t, 5.0f - std::sqrt(1.0f - 0.9999f * 0.9999f), 1e-4f);
  // Grazing an end circle: the hit at z exactly 2 counts (the surface is closed at its rims).
  EXPECT_FLOAT_EQ(intersect(kCylinder, ray_of({-5, 0, 2}, {1, 0, 0})), 4.0f);
}

TEST(Cone, AnalyticHits) {
  // Radius 0.75 at half height.
  EXPECT_FLOAT_EQ(intersect(kCone, ray_of({-5, 0, 0.5f}, {1, 0, 0})), 4.25f);
  // Along the axis of a sharp cone: the single root is the apex.
  EXPECT_FLOAT_EQ(intersect(kSharp, ray_of({0, 0, -5}, {0, 0, 1})), 7.0f);
  // Parallel to a generator line (x = 1 - z/2 in y = 0), so the quadratic term is zero: from
  // outside it never meets the surface; from inside it meets the far wall at the linear root,
  // (-0.25, 0, 1.5) where the radius is 0.25.
  EXPECT_FALSE(std::isfinite(intersect(kSharp, ray_of({1.5f, 0, 0}, {-0.5f, 0, 1}))));
  EXPECT_FLOAT_EQ(intersect(kSharp, ray_of({0.5f, 0, 0}, {-0.5f, 0, 1})), 1.5f);
  // The hit beyond the tip on the wrong nappe of the double cone is rejected.
  EXPECT_FALSE(std::isfinite(intersect(kSharp, ray_of({-5, 0, 3}, {1, 0, 0}))));
}

TEST(Cone, RandomRaysLandOnTheSurface) {
  const Cone tilted = make_cone(Vec3(1, -2, 0.5f), 0.8f, Vec3(2, 1, 3), 0.3f);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const Vec3 a = tilted.axis;
  const Vec3 e1 = glm::normalize(glm::cross(a, std::abs(a.x) < 0.9f ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
  const Vec3 e2 = glm::cross(a, e1);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    // A target on the surface and an origin far outside; the hit is at or before the target.
    const float z = u01(rng) * tilted.height;
    const float phi = 6.2831853f * u01(rng);
    const float r = 0.8f + (0.3f - 0.8f) * z / tilted.height;
    const Vec3 target = tilted.base + z * a + r * (std::cos(phi) * e1 + std::sin(phi) * e2);
    // From the outside, at least 0.1 off the tangent plane: a float target may lie a rounding
    // error outside the surface, so a tangent ray may legitimately miss it.
    const Vec3 jitter(u01(rng) - 0.5f, u01(rng) - 0.5f, u01(rng) - 0.5f);
    const Vec3 out = glm::normalize(normal_at(tilted, target) + jitter);
    const Vec3 org = target + 10.0f * out;
    const Ray ray = ray_of(org, target - org);
    const float t = intersect(tilted, ray);
    ASSERT_TRUE(std::isfinite(t)) << "ray " << i;
    EXPECT_LE(t, 1.0f + 1e-4f);
    const Vec3 p = org + t * (target - org);
    const float pz = glm::dot(p - tilted.base, a);
    const float dist = glm::length(p - tilted.base - pz * a);
    EXPECT_NEAR(dist, 0.8f + (0.3f - 0.8f) * pz / tilted.height, 1e-4f);
    ++hits;
  }
  EXPECT_EQ(hits, 2000);
}

TEST(Cone, TightBounds) {
  const Cone tilted = make_cone(Vec3(1, -2, 0.5f), 0.8f, Vec3(2, 1, 3), 0.3f);
  const accel::Aabb box = bounds(tilted);
  const Vec3 a = tilted.axis;
  const Vec3 e1 = glm::normalize(glm::cross(a, Vec3(1, 0, 0)));
  const Vec3 e2 = glm::cross(a, e1);
  accel::Aabb sampled;
  for (int i = 0; i < 3600; ++i) {
    const float phi = 6.2831853f * float(i) / 3600.0f;
    const Vec3 c = std::cos(phi) * e1 + std::sin(phi) * e2;
    for (const Vec3 p : {tilted.base + 0.8f * c, apex_of(tilted) + 0.3f * c}) {
      sampled.grow(p);
      EXPECT_TRUE(box.contains(accel::Aabb::of_point(p)));
    }
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(box.lo[k], sampled.lo[k], 1e-4f);
    EXPECT_NEAR(box.hi[k], sampled.hi[k], 1e-4f);
  }
  // Axis-aligned cylinder: the box is exactly the end discs.
  const accel::Aabb cb = bounds(kCylinder);
  EXPECT_NEAR(cb.lo.x, -1.0f, 1e-5f);
  EXPECT_NEAR(cb.hi.z, 2.0f, 1e-5f);
  EXPECT_NEAR(cb.lo.z, 0.0f, 1e-5f);
}

TEST(Cone, NormalsFaceTheVisibleSide) {
  EXPECT_NEAR(glm::length(normal_at(kCylinder, {1, 0, 1}) - Vec3(1, 0, 0)), 0.0f, 1e-6f);
  // The slope tilts the normal upwards for a cone narrowing upwards: (1, 0, 0.5) normalised.
  const Vec3 n = normal_at(kCone, {0.75f, 0, 0.5f});
  EXPECT_NEAR(glm::length(n - glm::normalize(Vec3(1, 0, 0.5f))), 0.0f, 1e-6f);
  const Cone inside = make_cone(Vec3(0, 0, 0), -1.0f, Vec3(0, 0, 2), -1.0f);
  EXPECT_NEAR(glm::length(normal_at(inside, {1, 0, 1}) - Vec3(-1, 0, 0)), 0.0f, 1e-6f);
  EXPECT_FLOAT_EQ(intersect(inside, ray_of({-5, 0, 1}, {1, 0, 0})), 4.0f);
}

}  // namespace
