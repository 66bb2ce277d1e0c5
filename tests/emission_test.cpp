// Photon emission (photon/emission.h): photons per light in proportion to power at every prefix,
// emitted powers summing to the lights' total, uniform directions over the sphere or the cone.

#include "photon/emission.h"
#include "photon/photon_rng.h"

#include "scenes_gen/materials.h"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace {

using photon::Color;
using photon::Vec3;

tracer::Scene three_lights() {
  tracer::Scene s;
  s.lights = {scenes_gen::point_light({0, 5, 0}, 1000.0f),
              scenes_gen::point_light({3, 5, 0}, 3000.0f, {1.0f, 0.5f, 0.0f}),  // mean colour 0.5
              scenes_gen::point_light({-3, 5, 0}, 500.0f),
              scenes_gen::point_light({0, 5, 3}, 0.0f)};  // emits nothing: never chosen
  s.materials = {scenes_gen::diffuse("floor", Color(0.5f))};
  s.geometry.planes.push_back({Vec3(0, 1, 0), 0.0f, 0});
  s.geometry.finalize();
  return s;
}

TEST(Emission, PhotonsPerLightFollowPowerAtEveryPrefix) {
  const tracer::Scene scene = three_lights();
  const photon::Emission e(scene, photon::PhotonPass::Global);
  ASSERT_EQ(e.lights().size(), 3u);
  // Shares by power x mean colour: 1000, 1500, 500 of 3000.
  const double share[3] = {1000.0 / 3000.0, 1500.0 / 3000.0, 500.0 / 3000.0};
  photon::LightSequence seq = e.sequence();
  double worst = 0.0;
  for (int n = 1; n <= 20000; ++n) {
    seq.next();
    for (int j = 0; j < 3; ++j)
      worst = std::max(worst, std::abs(double(seq.counts()[std::size_t(j)]) - n * share[j]));
  }
  EXPECT_LT(worst, 2.0) << "a light fell more than 2 photons behind or ahead of its share";
  EXPECT_EQ(seq.emitted(), 20000u);
  EXPECT_EQ(seq.counts()[0] + seq.counts()[1] + seq.counts()[2], 20000u);
}

TEST(Emission, PhotonPowersSumToTheLightsTotalAndAreNearlyEqual) {
  const tracer::Scene scene = three_lights();
  const photon::Emission e(scene, photon::PhotonPass::Global);
  for (int n : {1, 7, 1000, 99991}) {
    photon::LightSequence seq = e.sequence();
    for (int i = 0; i < n; ++i) seq.next();
    double sum[3] = {0, 0, 0};
    double lo = 1e300, hi = 0.0;
    for (std::uint32_t j = 0; j < 3; ++j) {
      const std::uint64_t nj = seq.counts()[j];
      if (nj == 0) continue;
      const Color p = e.photon_power(j, nj);
      for (int c = 0; c < 3; ++c) sum[c] += double(nj) * double(p[c]);
      const double scalar = (double(p.x) + double(p.y) + double(p.z)) / 3.0;
      lo = std::min(lo, scalar);
      hi = std::max(hi, scalar);
    }
    // Every light's total, per channel: 1000 + 3000 * (1, 0.5, 0) + 500 = (4500, 3000, 1500).
    const double want[3] = {4500.0, 3000.0, 1500.0};
    if (n >= 3) {
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], want[c], want[c] * 1e-6) << n << " " << c;
    }
    // Equal up to the rounding of n_j: P_j / n_j = (P / n) (n p_j / n_j) with |n_j - n p_j| < 2,
    // so any two differ by a factor below (1 + 2/n_min) / (1 - 2/n_min), about 1 + 4/n_min.
    const double n_min = n / 6.0 - 2.0;
    if (n >= 1000) {
      EXPECT_LT(hi / lo, (1.0 + 2.0 / n_min) / (1.0 - 2.0 / n_min)) << n;
    }
  }
}

TEST(Emission, DirectionsAreUniformOverTheSphere) {
  const tracer::Scene scene = three_lights();
  const photon::Emission e(scene, photon::PhotonPass::Global);
  Vec3 mean(0.0f);
  int up = 0;
  const int n = 40000;
  photon::PhotonRng rng(7, 0, 0);
  for (int i = 0; i < n; ++i) {
    const float u1 = rng.uniform(), u2 = rng.uniform();
    const accel::Ray r = e.emit(0, u1, u2);
    EXPECT_NEAR(glm::length(r.dir), 1.0f, 1e-5f);
    EXPECT_EQ(r.org, scene.lights[0].position);
    mean += r.dir;
    up += r.dir.y > 0.5f;  // a cap of 1/4 of the sphere
  }
  mean /= float(n);
  // Each component of a uniform unit vector has variance 1/3: mean within 4 sigma.
  for (int a = 0; a < 3; ++a) EXPECT_LT(std::abs(mean[a]), 4.0f * std::sqrt(1.0f / 3.0f / n));
  const double sigma = std::sqrt(n * 0.25 * 0.75);
  EXPECT_NEAR(up, n * 0.25, 4.0 * sigma);
}

TEST(Emission, CausticPassAimsAtTheSpecularPrimitivesWithTheConesPower) {
  tracer::Scene scene = three_lights();
  scene.materials.push_back(scenes_gen::glass("glass", 1.5f));
  scene.geometry.spheres.push_back({{0.0f, 1.0f, 0.0f}, 1.0f, 1});
  scene.geometry.finalize();
  const photon::Emission e(scene, photon::PhotonPass::Caustic);
  ASSERT_EQ(e.lights().size(), 3u);
  const photon::EmittingLight& l = e.lights()[0];  // at (0, 5, 0), 4 above the sphere's centre
  // The bounding sphere of the sphere's box: radius sqrt(3). Its cone from 4 units away.
  const double s = std::sqrt(3.0) / 4.0, cos_max = std::sqrt(1.0 - s * s);
  EXPECT_NEAR(l.cos_max, cos_max, 1e-6);
  EXPECT_NEAR(l.power.x, 1000.0 * (1.0 - cos_max) / 2.0, 1e-3);
  photon::PhotonRng rng(3, 1, 0);
  for (int i = 0; i < 2000; ++i) {
    const float u1 = rng.uniform(), u2 = rng.uniform();
    const accel::Ray r = e.emit(0, u1, u2);
    EXPECT_GE(glm::dot(r.dir, Vec3(0, -1, 0)), float(cos_max) - 1e-6f);
  }
  // No specular primitive: nothing to aim at, no emission.
  const photon::Emission none(three_lights(), photon::PhotonPass::Caustic);
  EXPECT_TRUE(none.empty());
}

}  // namespace
