// Density estimation (photon/density.h). On a plane of uniform photon density each filter's
// mean estimate has a known bias, derived in docs/photon-kdtree.md and checked here by Monte
// Carlo within 3 standard errors:
//   N photons uniform in a unit disc, the query at its centre, n of them gathered, r the n-th
//   distance. r^2 ~ Beta(n, N - n + 1), so E[1/(pi r^2)] = N / (pi (n - 1)) = lambda n/(n - 1)/n:
//   box       E = lambda n/(n - 1);
//   cone      the n - 1 nearer photons are uniform in the disc of radius r, E[d/r] = 2/3, so
//             E = lambda (1 + 3 (k - 1) / ((n - 1)(3 k - 2)));
//   biweight  E[(1 - d^2/r^2)^2] = 1/3 for those, 0 for the n-th: E = lambda exactly.

#include "photon/density.h"

#include "photon_sets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace {

using photon::Color;
using photon::DensityFilter;
using photon::DensityParams;
using photon::GatherParams;
using photon::Neighbors;
using photon::Photon;
using photon::PhotonMap;
using photon::PhotonTreeKind;
using photon::Vec3;

constexpr float kUnboundedRadius = std::numeric_limits<float>::infinity();
const Vec3 kUp(0.0f, 0.0f, 1.0f);
const Vec3 kDown(0.0f, 0.0f, -1.0f);

struct Estimate {
  double mean, stderr_;
};

/// Mean of estimate / truth over `trials` discs of N photons of power 1 W (exact in the record).
Estimate monte_carlo(const DensityParams& filter, int n, int N, int trials, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const double truth = N / std::numbers::pi;  // watts per unit area
  double sum = 0.0, sum2 = 0.0;
  std::vector<Photon> photons(static_cast<std::size_t>(N));
  Neighbors nb;
  for (int t = 0; t < trials; ++t) {
    for (Photon& p : photons) {
      const float rad = std::sqrt(u(rng)), phi = 2.0f * std::numbers::pi_v<float> * u(rng);
      p = Photon::make(Vec3(rad * std::cos(phi), rad * std::sin(phi), 0.0f), Color(1.0f), kDown);
    }
    const PhotonMap map(photons, {PhotonTreeKind::Balanced, 8});
    map.gather(Vec3(0.0f), kUp, GatherParams{n, 2.0f, true, true}, nb);
    const double ratio = photon::flux_density(map, nb, filter, kUp).x / truth;
    sum += ratio;
    sum2 += ratio * ratio;
  }
  const double mean = sum / trials;
  const double var = (sum2 / trials - mean * mean) * trials / (trials - 1);
  return {mean, std::sqrt(var / trials)};
}

double cone_bias(double k, int n) { return 1.0 + 3.0 * (k - 1.0) / ((n - 1) * (3.0 * k - 2.0)); }

TEST(Density, BoxMeanIsNOverNMinusOne) {
  for (const int n : {8, 50}) {
    const Estimate e = monte_carlo({DensityFilter::Box, 1.0f}, n, 400, 4000, 1 + n);
    const double want = double(n) / (n - 1);
    EXPECT_NEAR(e.mean, want, 3.0 * e.stderr_) << "n=" << n;
    EXPECT_GT(std::abs(want - 1.0), 3.0 * e.stderr_) << "the run cannot tell the bias from none";
  }
}

TEST(Density, ConeMeanMatchesItsBias) {
  for (const auto& [k, n] : {std::pair{2.0f, 8}, std::pair{1.1f, 8}, std::pair{10.0f, 50}}) {
    const Estimate e = monte_carlo({DensityFilter::Cone, k}, n, 400, 4000, 7 + n);
    const double want = cone_bias(k, n);
    EXPECT_NEAR(e.mean, want, 3.0 * e.stderr_) << "k=" << k << " n=" << n;
    if (k >= 2.0f) {
      EXPECT_GT(std::abs(want - 1.0), 3.0 * e.stderr_) << "k=" << k << " n=" << n;
    }
  }
  // The cone with k = 1 is unbiased.
  EXPECT_EQ(cone_bias(1.0, 8), 1.0);
}

TEST(Density, BiweightIsUnbiased) {
  for (const int n : {8, 50}) {
    const Estimate e = monte_carlo({DensityFilter::Biweight, 1.0f}, n, 400, 4000, 13 + n);
    EXPECT_NEAR(e.mean, 1.0, 3.0 * e.stderr_) << "n=" << n;
  }
}

std::vector<Photon> at(std::initializer_list<Vec3> positions, const Vec3& dir = kDown) {
  std::vector<Photon> out;
  for (const Vec3& p : positions) out.push_back(Photon::make(p, Color(1.0f), dir));
  return out;
}

TEST(Density, EmptyMapGivesZero) {
  const PhotonMap none;
  Neighbors nb;
  none.gather(Vec3(0.0f), kUp, GatherParams{10, 1.0f, true, true}, nb);
  EXPECT_EQ(photon::flux_density(none, nb, {}, kUp), Color(0.0f));
  EXPECT_EQ(photon::estimate_radius2(nb), 0.0f);
}

TEST(Density, FewerThanKUsesTheSearchDisc) {
  const PhotonMap map(at({{0.1f, 0, 0}, {0, 0.2f, 0}, {0, 0, 0.3f}, {5, 5, 5}}), {});
  Neighbors nb;
  map.gather(Vec3(0.0f), kUp, GatherParams{10, 0.5f, true, true}, nb);
  ASSERT_EQ(nb.size(), 3);
  EXPECT_EQ(photon::estimate_radius2(nb), 0.25f);
  const Color box = photon::flux_density(map, nb, {DensityFilter::Box, 1.0f}, kUp);
  EXPECT_FLOAT_EQ(box.x, float(3.0 / (std::numbers::pi * 0.25)));
  // Unbounded: the farthest photon found is the radius.
  map.gather(Vec3(0.0f), kUp, GatherParams{10, kUnboundedRadius, true, true}, nb);
  ASSERT_EQ(nb.size(), 4);
  EXPECT_EQ(photon::estimate_radius2(nb), 75.0f);
}

TEST(Density, CoincidentPhotonsUseTheSearchDisc) {
  const PhotonMap map(at({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {1, 1, 1}}), {});
  Neighbors nb;
  map.gather(Vec3(0.0f), kUp, GatherParams{3, 0.5f, true, true}, nb);
  ASSERT_TRUE(nb.full());
  EXPECT_EQ(nb.max_d2(), 0.0f);
  EXPECT_EQ(photon::estimate_radius2(nb), 0.25f);
  for (const DensityFilter f : {DensityFilter::Box, DensityFilter::Cone, DensityFilter::Biweight}) {
    const Color c = photon::flux_density(map, nb, {f, 1.0f}, kUp);
    EXPECT_TRUE(std::isfinite(c.x) && c.x > 0.0f) << photon::name_of(f);
  }
  // Unbounded and coincident: nothing to measure an area by.
  map.gather(Vec3(0.0f), kUp, GatherParams{3, kUnboundedRadius, true, true}, nb);
  EXPECT_EQ(photon::flux_density(map, nb, {DensityFilter::Box, 1.0f}, kUp), Color(0.0f));
}

TEST(Density, PhotonsFromBehindAreLeftOut) {
  std::vector<Photon> photons = at({{0.1f, 0, 0}, {0, 0.1f, 0}});
  photons.push_back(Photon::make(Vec3(-0.1f, 0, 0), Color(1.0f), kUp));  // from below
  const PhotonMap map(photons, {});
  Neighbors nb;
  // Gathered without culling (all three), estimated with the normal: two count.
  map.gather(Vec3(0.0f), kUp, GatherParams{3, 1.0f, false, true}, nb);
  ASSERT_EQ(nb.size(), 3);
  const float r2 = photon::estimate_radius2(nb);
  const Color c = photon::flux_density(map, nb, {DensityFilter::Box, 1.0f}, kUp);
  EXPECT_FLOAT_EQ(c.x, float(2.0 / (std::numbers::pi * r2)));
}

TEST(Density, SameBitsFromEveryTreeVariant) {
  const auto photons = photon_sets::make_set(photon_sets::SetKind::Clustered, 5000, 3);
  const auto queries = photon_sets::make_queries(photons, 200, 4);
  std::vector<PhotonMap> maps;
  maps.emplace_back(photons, photon::PhotonTreeParams{PhotonTreeKind::BruteForce, 8});
  maps.emplace_back(photons, photon::PhotonTreeParams{PhotonTreeKind::Balanced, 8});
  maps.emplace_back(photons, photon::PhotonTreeParams{PhotonTreeKind::SlidingMidpoint, 4});
  maps.emplace_back(photons, photon::PhotonTreeParams{PhotonTreeKind::MedianBuckets, 16});
  Neighbors nb;
  for (const DensityFilter f : {DensityFilter::Box, DensityFilter::Cone, DensityFilter::Biweight}) {
    for (const Vec3& q : queries) {
      Color first;
      for (std::size_t m = 0; m < maps.size(); ++m) {
        maps[m].gather(q, kUp, GatherParams{40, 0.2f, false, m % 2 == 0}, nb);
        const Color c = photon::flux_density(maps[m], nb, {f, 1.3f}, kUp);
        if (m == 0) first = c;
        EXPECT_EQ(c, first) << photon::name_of(f) << " map " << m;
      }
    }
  }
}

TEST(Density, BadConeKNamesTheKnob) {
  const PhotonMap map(at({{0, 0, 0}}), {});
  Neighbors nb;
  map.gather(Vec3(0.0f), kUp, GatherParams{1, 1.0f, true, true}, nb);
  try {
    photon::flux_density(map, nb, {DensityFilter::Cone, 0.5f}, kUp);
    FAIL() << "no error";
  } catch (const knobs::ConfigError& e) {
    EXPECT_STREQ(e.what(), "density: knob 'cone_k' must be in [1.0, 1000000.0], got 0.5");
  }
  try {
    nlohmann::json::parse(R"({"filter": "cone", "cone_k": 0.9})").get<DensityParams>();
    FAIL() << "no error";
  } catch (const knobs::ConfigError& e) {
    EXPECT_STREQ(e.what(), "density: knob 'cone_k' must be in [1.0, 1000000.0], got 0.9");
  }
  try {
    nlohmann::json::parse(R"({"filter": "gauss"})").get<DensityParams>();
    FAIL() << "no error";
  } catch (const knobs::ConfigError& e) {
    EXPECT_STREQ(e.what(), "density: knob 'filter' must be one of box|cone|biweight, got \"gauss\"");
  }
  const DensityParams p = nlohmann::json(DensityParams{DensityFilter::Biweight, 2.5f}).get<DensityParams>();
  EXPECT_EQ(p.filter, DensityFilter::Biweight);
  EXPECT_EQ(p.cone_k, 2.5f);
}

}  // namespace
