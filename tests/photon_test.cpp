// The photon record (photon/photon.h): 20 bytes, power within 1/255.5 of the largest channel
// (exact for equal channels with an 8-bit mantissa), direction within 0.8 degrees.

#include "photon/photon.h"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace {

using photon::Color;
using photon::Photon;
using photon::Vec3;

TEST(Photon, RecordIsTwentyBytes) {
  EXPECT_EQ(sizeof(Photon), 20u);
  EXPECT_EQ(sizeof(Vec3), 12u);
}

TEST(Photon, PowerWithinOne255point5thOfTheLargestChannel) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 1.0f), expo(-120.0f, 100.0f);
  float worst = 0.0f;
  for (int i = 0; i < 200000; ++i) {
    const float scale = std::exp2(expo(rng));
    const Color c = Color(u(rng), u(rng), u(rng)) * scale;
    const Color d = photon::unpack_power(photon::pack_power(c));
    const float m = std::max(c.x, std::max(c.y, c.z));
    for (int a = 0; a < 3; ++a) worst = std::max(worst, std::abs(d[a] - c[a]) / m);
  }
  EXPECT_LE(worst, photon::kPowerRelativeError);
  EXPECT_GT(worst, 1.0f / 256.0f) << "the bound is not tight: rounding changed?";
}

TEST(Photon, EqualPowersOfTwoAndSmallMantissasAreExact) {
  for (const float v : {1.0f, 0.5f, 0.75f, 1024.0f, 3.0f, std::ldexp(1.0f, -100), std::ldexp(255.0f, 60)}) {
    EXPECT_EQ(photon::unpack_power(photon::pack_power(Color(v))), Color(v)) << v;
  }
  // A typical emitted photon power, 100 W / 10^5 photons: the stored value and its error.
  const float phi = 100.0f / 1e5f;
  const float stored = photon::unpack_power(photon::pack_power(Color(phi))).x;
  EXPECT_LE(std::abs(stored - phi) / phi, photon::kPowerRelativeError);
}

TEST(Photon, PowerEdgeValues) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::nanf("");
  EXPECT_EQ(photon::unpack_power(photon::pack_power(Color(0.0f))), Color(0.0f));
  EXPECT_EQ(photon::unpack_power(photon::pack_power(Color(-1.0f, nan, 2.0f))), Color(0.0f, 0.0f, 2.0f));
  EXPECT_EQ(photon::unpack_power(photon::pack_power(Color(1e-42f))), Color(0.0f));
  const Color big = photon::unpack_power(photon::pack_power(Color(inf, 1.0f, 0.0f)));
  EXPECT_EQ(big.x, std::ldexp(255.0f, 111));
  EXPECT_TRUE(std::isfinite(big.x));
  // Rounding up into the next exponent: 255.6 -> 256.
  EXPECT_EQ(photon::unpack_power(photon::pack_power(Color(255.6f))).x, 256.0f);
  // Denormal photon powers keep their relative accuracy.
  const float tiny = std::ldexp(1.3f, -130);
  EXPECT_NEAR(photon::unpack_power(photon::pack_power(Color(tiny))).x / tiny, 1.0f,
              photon::kPowerRelativeError);
}

TEST(Photon, DirectionWithinPointEightDegrees) {
  std::mt19937 rng(2);
  std::normal_distribution<float> g(0.0f, 1.0f);
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    Vec3 d(g(rng), g(rng), g(rng));
    if (glm::length(d) < 1e-3f) continue;
    d = glm::normalize(d);
    const Vec3 back = Photon::make(Vec3(0.0f), Color(1.0f), d).direction();
    EXPECT_NEAR(glm::length(back), 1.0f, 1e-6f);
    const double angle = std::acos(std::min(1.0, double(glm::dot(back, d))));
    worst = std::max(worst, angle);
  }
  const double bound = std::hypot(std::numbers::pi / 508.0, std::numbers::pi / 256.0);
  EXPECT_LE(worst, bound);
  EXPECT_LT(worst * 180.0 / std::numbers::pi, 0.8);
}

TEST(Photon, AxisDirectionsAreExactAndZeroIsPlusZ) {
  const Vec3 axes[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const Vec3& a : axes) {
    const Vec3 back = Photon::make(Vec3(0.0f), Color(1.0f), a * 3.0f).direction();
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], a[c], 1e-7f) << a.x << a.y << a.z;
  }
  EXPECT_EQ(Photon::make(Vec3(0.0f), Color(1.0f), Vec3(0.0f)).direction(), Vec3(0.0f, 0.0f, 1.0f));
}

TEST(Photon, HemisphereTest) {
  // Travelling down onto a floor whose normal is +y: arrives from the normal's side.
  const Photon down = Photon::make(Vec3(0.0f), Color(1.0f), Vec3(0.3f, -1.0f, 0.2f));
  EXPECT_TRUE(down.arrives_from_side_of(Vec3(0.0f, 1.0f, 0.0f)));
  EXPECT_FALSE(down.arrives_from_side_of(Vec3(0.0f, -1.0f, 0.0f)));
  const Photon make = Photon::make(Vec3(1.0f, 2.0f, 3.0f), Color(0.25f), Vec3(0.0f, 0.0f, -1.0f));
  EXPECT_EQ(make.position, Vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(make.power(), Color(0.25f));
  EXPECT_EQ(make.flags, 0);
}

}  // namespace
