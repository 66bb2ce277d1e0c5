#include "tracer/sphere.h"

#include <gtest/gtest.h>

#include <random>

namespace {

using tracer::Ray;
using tracer::Vec3;

// A unit sphere at distance 1e4 and 1e5, in float: rays 1.1 radii off centre miss, rays within
// 0.9 radii hit on the surface. The naive b^2 - c discriminant fails this at 1e4.
class FarSphere : public ::testing::TestWithParam<float> {};

TEST_P(FarSphere, HitsAndMissesAreExact) {
  const float dist = GetParam();
  const Vec3 center(0.0f, 0.0f, -dist);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> angle(0.0f, 6.2831853f);
  for (int i = 0; i < 1000; ++i) {
    const float phi = angle(rng);
    const Vec3 off(std::cos(phi), std::sin(phi), 0.0f);
    for (float frac : {0.0f, 0.3f, 0.6f, 0.9f}) {
      Ray ray;
      ray.dir = glm::normalize(center + frac * off - ray.org);
      const float t = tracer::intersect_sphere(center, 1.0f, ray);
      ASSERT_TRUE(std::isfinite(t)) << "frac " << frac << " at distance " << dist;
      const Vec3 p = ray.org + t * ray.dir;
      EXPECT_NEAR(glm::length(p - center), 1.0f, 1e-3f * dist);
    }
    Ray miss;
    miss.dir = glm::normalize(center + 1.1f * off - miss.org);
    EXPECT_FALSE(std::isfinite(tracer::intersect_sphere(center, 1.0f, miss)));
  }
}

INSTANTIATE_TEST_SUITE_P(Distances, FarSphere, ::testing::Values(1e4f, 1e5f));

TEST(Sphere, FromInsideReturnsFarRoot) {
  Ray ray;
  ray.dir = Vec3(0, 0, 1);
  EXPECT_FLOAT_EQ(tracer::intersect_sphere(Vec3(0.0f), 2.0f, ray), 2.0f);
}

}  // namespace
