// Refracted directions: unit length, in the plane of incidence, and obeying Snell's law.

#include "tracer/optics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

using tracer::Vec3;

Vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<float> g(0.0f, 1.0f);
  for (;;) {
    const Vec3 v(g(rng), g(rng), g(rng));
    const float len = glm::length(v);
    if (len > 1e-3f) return v / len;
  }
}

TEST(Snell, RandomDirectionsObeyTheLawInBothDirections) {
  std::mt19937 rng(2024);
  int refracted = 0, total_internal = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 n = random_unit(rng);
    Vec3 d = random_unit(rng);
    if (glm::dot(d, n) > 0.0f) d = -d;  // arriving against n
    for (auto [eta1, eta2] : {std::pair{1.0f, 1.5f}, std::pair{1.5f, 1.0f}, std::pair{1.0f, 2.42f},
                              std::pair{1.33f, 1.0f}}) {
      Vec3 t;
      if (!tracer::refract(d, n, eta1 / eta2, t)) {
        // Only beyond the critical angle.
        const double sin1 = std::sqrt(std::max(0.0, 1.0 - double(glm::dot(d, n)) * glm::dot(d, n)));
        EXPECT_GE(eta1 / eta2 * sin1, 1.0 - 1e-6);
        ++total_internal;
        continue;
      }
      ++refracted;
      EXPECT_NEAR(glm::length(t), 1.0f, 1e-6f);
      // Coplanar: t lies in the plane spanned by d and n.
      const Vec3 plane_normal = glm::cross(d, n);
      if (glm::length(plane_normal) > 1e-3f) {
        EXPECT_NEAR(glm::dot(t, glm::normalize(plane_normal)), 0.0f, 1e-6f);
      }
      // Goes through: to the far side of the surface.
      EXPECT_LE(glm::dot(t, n), 0.0f);
      // eta1 sin1 = eta2 sin2.
      const float sin1 = glm::length(glm::cross(d, n));
      const float sin2 = glm::length(glm::cross(t, n));
      EXPECT_NEAR(eta1 * sin1, eta2 * sin2, 1e-6f) << "eta " << eta1 << "/" << eta2;
    }
  }
  EXPECT_GT(refracted, 50000);
  EXPECT_GT(total_internal, 1000);
}

TEST(Snell, NormalIncidenceGoesStraightThrough) {
  Vec3 t;
  ASSERT_TRUE(tracer::refract(Vec3(0.0f, -1.0f, 0.0f), Vec3(0.0f, 1.0f, 0.0f), 1.0f / 1.5f, t));
  EXPECT_EQ(t, Vec3(0.0f, -1.0f, 0.0f));
}

TEST(Optics, ReflectMirrorsAboutTheNormal) {
  const Vec3 r = tracer::reflect(glm::normalize(Vec3(1.0f, -1.0f, 0.0f)), Vec3(0.0f, 1.0f, 0.0f));
  EXPECT_NEAR(r.x, std::sqrt(0.5f), 1e-7f);
  EXPECT_NEAR(r.y, std::sqrt(0.5f), 1e-7f);
  EXPECT_EQ(r.z, 0.0f);
}

TEST(Optics, OrientTellsInsideFromOutsideBySignOfDDotN) {
  const Vec3 n(0.0f, 0.0f, 1.0f);
  const tracer::Interface in = tracer::orient(glm::normalize(Vec3(0.2f, 0.0f, -1.0f)), n, 1.5f);
  EXPECT_TRUE(in.entering);
  EXPECT_EQ(in.eta_i, 1.0f);
  EXPECT_EQ(in.eta_t, 1.5f);
  EXPECT_EQ(in.normal, n);
  const tracer::Interface out = tracer::orient(glm::normalize(Vec3(0.2f, 0.0f, 1.0f)), n, 1.5f);
  EXPECT_FALSE(out.entering);
  EXPECT_EQ(out.eta_i, 1.5f);  // leaving glass: eta = n_glass / n_air
  EXPECT_EQ(out.eta_t, 1.0f);
  EXPECT_EQ(out.normal, -n);
  EXPECT_GT(out.cos_i, 0.9f);
}

}  // namespace
