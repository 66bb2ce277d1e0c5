// Fresnel reflectance at a smooth dielectric: the textbook values, energy conservation,
// reciprocity, and the extremes (eta = 1, the critical angle to the ulp, eta = 1e20).

#include "tracer/optics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

using tracer::fresnel_dielectric;
using tracer::refract;
using tracer::Vec3;

constexpr double kPi = 3.14159265358979323846;

TEST(Fresnel, NormalIncidenceAirToGlassIsFourPercent) {
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.0f, 1.5f), 0.04f, 1e-7f);
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.5f, 1.0f), 0.04f, 1e-7f);  // same from inside
}

TEST(Fresnel, BrewsterAngleReflectsOnlyThePerpendicularHalf) {
  const double theta_b = std::atan(1.5);
  const float cos_b = float(std::cos(theta_b));
  // At Brewster's angle R_par = 0, so R = R_perp / 2 = ((cos_i - n cos_t)/(cos_i + n cos_t))^2 / 2
  // with cos_t = sin_i / n ... = 0.0739645 for n = 1.5.
  EXPECT_NEAR(fresnel_dielectric(cos_b, 1.0f, 1.5f), 0.0739645f, 1e-6f);
}

TEST(Fresnel, GrazingIncidenceReflectsEverything) {
  EXPECT_EQ(fresnel_dielectric(0.0f, 1.0f, 1.5f), 1.0f);
  EXPECT_EQ(fresnel_dielectric(0.0f, 1.5f, 1.0f), 1.0f);
}

TEST(Fresnel, ReflectanceAndTransmittanceSumToOneAndStayInRange) {
  for (float eta_t : {1.0f, 1.33f, 1.5f, 2.4f}) {
    for (int i = 0; i <= 1000; ++i) {
      const float cos_i = float(i) / 1000.0f;
      for (auto [a, b] : {std::pair{1.0f, eta_t}, std::pair{eta_t, 1.0f}}) {
        const float r = fresnel_dielectric(cos_i, a, b);
        const float t = 1.0f - r;
        ASSERT_TRUE(r >= 0.0f && r <= 1.0f) << "cos " << cos_i << " eta " << a << "/" << b;
        EXPECT_FLOAT_EQ(r + t, 1.0f);
      }
    }
  }
}

TEST(Fresnel, ReciprocityBetweenTheTwoSides) {
  // R(theta_i; n1, n2) = R(theta_t; n2, n1) for the transmitted angle theta_t.
  for (int i = 1; i < 100; ++i) {
    const double theta_i = (kPi / 2) * i / 100.0;
    const double sin_t = std::sin(theta_i) / 1.5;
    const float cos_t = float(std::sqrt(1.0 - sin_t * sin_t));
    const float cos_i = float(std::cos(theta_i));
    // Near grazing R is steep in cos_i, so float rounding of the cosines weighs more there.
    EXPECT_NEAR(fresnel_dielectric(cos_i, 1.0f, 1.5f), fresnel_dielectric(cos_t, 1.5f, 1.0f),
                2e-6f / cos_i)
        << "theta_i " << theta_i;
  }
}

TEST(Fresnel, EqualIndicesReflectNothingAndBendNothingEvenAtGrazing) {
  for (float cos_i : {1.0f, 0.5f, 1e-3f, 1e-30f, 0.0f}) {
    EXPECT_EQ(fresnel_dielectric(cos_i, 1.0f, 1.0f), 0.0f) << cos_i;
    EXPECT_EQ(fresnel_dielectric(cos_i, 1.7f, 1.7f), 0.0f) << cos_i;
  }
  const float sin_i = 1.0f, cos_i = 0.0f;  // exactly grazing
  const Vec3 n(0.0f, 0.0f, 1.0f);
  for (const Vec3& d : {Vec3(sin_i, 0.0f, -cos_i), glm::normalize(Vec3(1.0f, 1.0f, -1e-6f)),
                        glm::normalize(Vec3(0.3f, -0.2f, -0.9f))}) {
    Vec3 t(-7.0f);
    ASSERT_TRUE(refract(d, n, 1.0f, t));
    EXPECT_EQ(t, d);  // bit for bit
  }
}

/// The float cosine at which light inside glass (1.5 -> 1) starts to be totally reflected:
/// refraction exists at `below` and not at `above`, one ulp apart.
void critical_pair(float& above, float& below) {
  float c = float(std::sqrt(1.0 - 1.0 / (1.5 * 1.5)));  // near the critical cosine
  float cos_t = 0.0f;
  // Walk to the exact float boundary of the transmitted_cos decision.
  while (tracer::transmitted_cos(c, 1.5f, cos_t)) c = std::nextafter(c, 0.0f);
  while (!tracer::transmitted_cos(c, 1.5f, cos_t)) c = std::nextafter(c, 1.0f);
  below = c;                        // first cosine that transmits
  above = std::nextafter(c, 0.0f);  // one ulp more grazing: total internal reflection
}

TEST(Fresnel, OneUlpEitherSideOfTheCriticalAngle) {
  float tir = 0.0f, ok = 0.0f;
  critical_pair(tir, ok);
  ASSERT_EQ(std::nextafter(tir, 1.0f), ok);
  EXPECT_NEAR(ok, std::sqrt(1.0 - 1.0 / 2.25), 1e-6);

  // Total internal reflection side: R = 1, no refracted ray.
  EXPECT_EQ(fresnel_dielectric(tir, 1.5f, 1.0f), 1.0f);
  const Vec3 n(0.0f, 0.0f, 1.0f);
  const Vec3 d_tir(std::sqrt(1.0f - tir * tir), 0.0f, -tir);
  Vec3 t(0.0f);
  EXPECT_FALSE(refract(d_tir, n, 1.5f, t));

  // Refracting side: finite R <= 1, a finite unit direction, no NaN.
  const float r = fresnel_dielectric(ok, 1.5f, 1.0f);
  EXPECT_TRUE(std::isfinite(r));
  EXPECT_LE(r, 1.0f);
  EXPECT_GE(r, 0.0f);
  const Vec3 d_ok(std::sqrt(1.0f - ok * ok), 0.0f, -ok);
  ASSERT_TRUE(refract(d_ok, n, 1.5f, t));
  for (int a = 0; a < 3; ++a) EXPECT_TRUE(std::isfinite(t[a]));
  EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f);
  EXPECT_LE(t.z, 0.0f);  // goes through, nearly grazing
}

TEST(Fresnel, HugeIndexRatioStaysFinite) {
  for (float cos_i : {1.0f, 0.7f, 1e-4f, 0.0f}) {
    for (auto [a, b] : {std::pair{1.0f, 1e20f}, std::pair{1e20f, 1.0f}, std::pair{1e-20f, 1e20f},
                        std::pair{1e20f, 1e-20f}}) {
      const float r = fresnel_dielectric(cos_i, a, b);
      EXPECT_TRUE(std::isfinite(r)) << cos_i << " " << a << " " << b;
      EXPECT_GE(r, 0.0f);
      EXPECT_LE(r, 1.0f);
    }
  }
  // Into an (almost) infinitely dense medium nearly everything reflects.
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.0f, 1e20f), 1.0f, 1e-6f);
  // Out of it: total internal reflection off normal, and a finite refraction along the normal.
  const Vec3 n(0.0f, 0.0f, 1.0f);
  Vec3 t(0.0f);
  ASSERT_TRUE(refract(Vec3(0.0f, 0.0f, -1.0f), n, 1e20f, t));
  EXPECT_EQ(t, Vec3(0.0f, 0.0f, -1.0f));
  EXPECT_FALSE(refract(glm::normalize(Vec3(0.01f, 0.0f, -1.0f)), n, 1e20f, t));
  ASSERT_TRUE(refract(glm::normalize(Vec3(0.6f, 0.0f, -0.8f)), n, 1e-20f, t));
  for (int a = 0; a < 3; ++a) EXPECT_TRUE(std::isfinite(t[a]));
}

}  // namespace
