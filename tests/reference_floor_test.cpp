// The floor of a progressive reference (harness/reference_floor.h) on synthetic stages whose
// truth, bias and noise are known: the plain estimator's bias and noise are recovered,
// Richardson's cancels a pure N^-p bias, and what it leaves of a faster term is over-, never
// under-estimated.

#include "harness/reference_floor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace {

constexpr int kW = 200, kH = 150;
constexpr double kOrder = 1.0 / 3.0;
constexpr double kStages = 512.0;  // N; checkpoints at N/8 and N/64

/// A synthetic progressive estimator per channel value: truth t, bias beta N^-p + gamma N^-2p,
/// noise sigma N^-p (independent draws at each stage and half).
struct Synthetic {
  std::vector<double> truth, beta, gamma;
  double sigma = 0.0;
  double bias_order = kOrder;  ///< The order of the beta term (the theory's unless set).

  Synthetic(double gamma_scale, double sigma_, std::uint32_t seed, double order = kOrder)
      : sigma(sigma_), bias_order(order) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < kW * kH * 3; ++i) {
      truth.push_back(2.0 * u(rng));
      beta.push_back(2.0 * u(rng) - 1.0);
      gamma.push_back(gamma_scale * (2.0 * u(rng) - 1.0));
    }
  }
  tracer::Image stage(double n, std::mt19937& rng) const {
    std::normal_distribution<double> z(0.0, 1.0);
    tracer::Image img(kW, kH);
    for (int i = 0; i < kW * kH; ++i)
      for (int c = 0; c < 3; ++c) {
        const std::size_t v = std::size_t(i) * 3 + std::size_t(c);
        const double x = truth[v] + beta[v] * std::pow(n, -bias_order) + gamma[v] * std::pow(n, -2.0 * kOrder) +
                         sigma * std::pow(n, -kOrder) * z(rng);
        img.at(i % kW, i / kW)[c] = float(x);
      }
    return img;
  }
  harness::HalfStages half(std::uint32_t seed) const {
    std::mt19937 rng(seed);
    return {stage(kStages, rng), stage(kStages / 8, rng), stage(kStages / 64, rng)};
  }
  /// RMS over values of f(v).
  template <class F>
  double rms(F f) const {
    double s = 0.0;
    for (std::size_t v = 0; v < truth.size(); ++v) s += f(v) * f(v);
    return std::sqrt(s / double(truth.size()));
  }
  double rmse_to_truth(const tracer::Image& img) const {
    return rms([&](std::size_t v) { return double(img.pixels()[v / 3][int(v % 3)]) - truth[v]; });
  }
};

TEST(ReferenceFloor, PlainRecoversItsBiasAndNoise) {
  const Synthetic s(0.0, 0.5, 1);
  const harness::ProgressiveReference r =
      harness::progressive_reference(s.half(2), s.half(3), kOrder, harness::ReferenceEstimator::Plain, 1e-2);
  const double bias = s.rms([&](std::size_t v) { return s.beta[v] * std::pow(kStages, -kOrder); });
  const double noise = s.sigma * std::pow(kStages, -kOrder) / std::sqrt(2.0);  // the mean of two halves
  EXPECT_NEAR(std::sqrt(r.bias_mse.value), bias, 0.05 * bias);
  EXPECT_GE(r.bias_mse.upper, r.bias_mse.value);
  EXPECT_NEAR(std::sqrt(r.noise_mse), noise, 0.05 * noise);
  // Together they are the reference's true error.
  EXPECT_NEAR(std::sqrt(r.noise_mse + r.bias_mse.value), s.rmse_to_truth(r.image), 0.05 * s.rmse_to_truth(r.image));
  EXPECT_GT(r.bias_rel.value, 0.0);
  EXPECT_GT(r.noise_rel, 0.0);
}

// A bias that falls as N^-0.2 instead of the theory's N^-1/3 (an edge's blur, of order R, falls
// as N^-1/6): taking the theory on trust, D = L_N - L_N/8 would stand for 0.74 of the bias. The
// stage before shows the slower fall, and the bound follows it.
TEST(ReferenceFloor, PlainMeasuresABiasThatFallsMoreSlowly) {
  constexpr double kSlow = 0.2;
  const Synthetic s(0.0, 0.5, 21, kSlow);
  harness::HalfStages a = s.half(22), b = s.half(23);
  const harness::ProgressiveReference r =
      harness::progressive_reference(a, b, kOrder, harness::ReferenceEstimator::Plain, 1e-2);
  const double bias = s.rms([&](std::size_t v) { return s.beta[v] * std::pow(kStages, -kSlow); });
  EXPECT_NEAR(std::sqrt(r.bias_mse.value), bias, 0.05 * bias);
  EXPECT_NEAR(r.bias_order, kSlow, 0.01);
  EXPECT_NEAR(std::sqrt(r.noise_mse + r.bias_mse.value), s.rmse_to_truth(r.image), 0.05 * s.rmse_to_truth(r.image));
  // Without the N/64 stage the rate cannot be measured: the theory's, and 0.74 of the bias.
  a.n64 = b.n64 = tracer::Image();
  const harness::ProgressiveReference trusting =
      harness::progressive_reference(a, b, kOrder, harness::ReferenceEstimator::Plain, 1e-2);
  EXPECT_NEAR(trusting.bias_order, kOrder, 1e-12);
  const double g = std::pow(8.0, kOrder), g_slow = std::pow(8.0, kSlow);
  EXPECT_NEAR(std::sqrt(trusting.bias_mse.value), bias * (g_slow - 1.0) / (g - 1.0), 0.05 * bias);
}

// Stages whose bias falls more slowly than an edge's (the first passes, before the radius
// shrinks) are bounded at the edge's order, half the theory's.
TEST(ReferenceFloor, PlainBoundsTheRateAtAnEdgesOrder) {
  const Synthetic s(0.0, 0.5, 27, 0.08);
  const harness::ProgressiveReference r =
      harness::progressive_reference(s.half(28), s.half(29), kOrder, harness::ReferenceEstimator::Plain, 1e-2);
  EXPECT_NEAR(r.bias_order, kOrder / 2.0, 1e-12);
  const double bias = s.rms([&](std::size_t v) { return s.beta[v] * std::pow(kStages, -0.08); });
  const double g_edge = std::pow(8.0, kOrder / 2.0), g_slow = std::pow(8.0, 0.08);
  EXPECT_NEAR(std::sqrt(r.bias_mse.value), bias * (g_slow - 1.0) / (g_edge - 1.0), 0.05 * bias);
}

// A bias that falls faster than the theory is bounded at the theory's rate (never a smaller bound).
TEST(ReferenceFloor, PlainNeverAssumesAFasterFall) {
  const Synthetic s(0.0, 0.5, 24, 0.5);
  const harness::ProgressiveReference r =
      harness::progressive_reference(s.half(25), s.half(26), kOrder, harness::ReferenceEstimator::Plain, 1e-2);
  EXPECT_NEAR(r.bias_order, kOrder, 1e-12);
  EXPECT_GE(std::sqrt(r.bias_mse.value), s.rms([&](std::size_t v) { return s.beta[v] * std::pow(kStages, -0.5); }));
}

TEST(ReferenceFloor, RichardsonCancelsTheLeadingBias) {
  const Synthetic s(0.0, 0.1, 4);
  const harness::ProgressiveReference plain =
      harness::progressive_reference(s.half(5), s.half(6), kOrder, harness::ReferenceEstimator::Plain, 1e-2);
  const harness::ProgressiveReference rich =
      harness::progressive_reference(s.half(5), s.half(6), kOrder, harness::ReferenceEstimator::Richardson, 1e-2);
  // No bias left, and its estimate says so (its upper bound is a few standard errors).
  const double plain_bias = std::sqrt(plain.bias_mse.value);
  EXPECT_LT(std::sqrt(rich.bias_mse.upper), 0.2 * plain_bias);
  // Its error against the truth is its noise alone, which is larger than plain's: (g L_N - L_N/8)
  // with g = 2 weighs the noisier early stage in.
  EXPECT_NEAR(s.rmse_to_truth(rich.image), std::sqrt(rich.noise_mse), 0.05 * std::sqrt(rich.noise_mse));
  EXPECT_GT(rich.noise_mse, 2.0 * plain.noise_mse);
}

TEST(ReferenceFloor, RichardsonOverestimatesWhatAFasterTermLeaves) {
  // gamma N^-2p remains after cancelling N^-p: -g gamma N^-2p. Its estimate from one stage
  // earlier sees (g^2 - 1)/(g - 1) = 3 times that (a residual of order 2p, not p).
  const Synthetic s(40.0, 0.05, 7);
  const harness::ProgressiveReference rich =
      harness::progressive_reference(s.half(8), s.half(9), kOrder, harness::ReferenceEstimator::Richardson, 1e-2);
  const double g = std::pow(8.0, kOrder);
  const double residual = s.rms([&](std::size_t v) { return g * s.gamma[v] * std::pow(kStages, -2.0 * kOrder); });
  const double estimate = std::sqrt(rich.bias_mse.value);
  EXPECT_GE(estimate, residual);
  EXPECT_NEAR(estimate, (g + 1.0) * residual, 0.1 * (g + 1.0) * residual);
}

/// A 160 x 120 field of per-pixel values (as the fronts' references are): mean mu, plus a
/// value shared by every pixel of each `blob` x `blob` square (a bias that sits in blobs), plus
/// a little noise of each pixel's own.
std::vector<double> blob_field(double mu, int blob, std::uint32_t seed) {
  constexpr int w = 160, h = 120;
  std::mt19937 rng(seed);
  std::normal_distribution<double> z(0.0, 1.0);
  const int bw = (w + blob - 1) / blob, bh = (h + blob - 1) / blob;
  std::vector<double> shared(std::size_t(bw) * std::size_t(bh));
  for (double& v : shared) v = z(rng);
  std::vector<double> s(std::size_t(w) * std::size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      s[std::size_t(y) * w + std::size_t(x)] = mu + shared[std::size_t(y / blob) * std::size_t(bw) + std::size_t(x / blob)] +
                                                 0.1 * z(rng);
  return s;
}

// Where the values are correlated over 32 x 32 blobs, 8 x 8 blocks see 16 times too many
// independent pieces and their standard error is about 4x too small: the 95% bound of their mean
// fell below the true mean in about a third of the fields. The bound takes the largest standard
// error over block sides 8, 16 and 32 (20 blocks of 32 at 160 x 120), so it holds about as often
// as a 95% bound from 20 blocks should.
TEST(ReferenceFloor, TheBoundHoldsWhereTheValuesShareBlobsLargerThanABlock) {
  constexpr double mu = 6.0;  // 2 per channel value
  int below = 0, trials = 400;
  for (int t = 0; t < trials; ++t) {
    const harness::MeanEstimate m = harness::block_mean_upper(blob_field(mu, 32, std::uint32_t(100 + t)), 160, 120);
    if (m.upper < mu / 3.0) ++below;
  }
  EXPECT_LE(below, trials / 10) << below << " of " << trials << " bounds below the true mean";
}

// Without correlation beyond a pixel the larger blocks change little: the bound stays about as
// tight as single pixels' spread would make it.
TEST(ReferenceFloor, TheBoundStaysTightWhereThePixelsAreIndependent) {
  const std::vector<double> s = blob_field(6.0, 1, 7);  // every pixel its own "blob"
  const harness::MeanEstimate m = harness::block_mean_upper(s, 160, 120);
  const double pixel_se = 1.005 / std::sqrt(160.0 * 120.0) / 3.0;  // sqrt(1 + 0.1^2) per pixel
  EXPECT_NEAR(m.upper - m.value, 1.96 * pixel_se, 0.6 * 1.96 * pixel_se);
  EXPECT_THROW(harness::block_mean_upper(s, 160, 119), std::invalid_argument);
}

TEST(ReferenceFloor, BadInputIsRefused) {
  const Synthetic s(0.0, 0.5, 10);
  harness::HalfStages a = s.half(11), b = s.half(12);
  EXPECT_THROW(harness::progressive_reference(a, b, 0.0, harness::ReferenceEstimator::Plain, 1e-2),
               std::invalid_argument);
  b.n64 = tracer::Image();
  EXPECT_NO_THROW(harness::progressive_reference(a, b, kOrder, harness::ReferenceEstimator::Plain, 1e-2));
  EXPECT_THROW(harness::progressive_reference(a, b, kOrder, harness::ReferenceEstimator::Richardson, 1e-2),
               std::invalid_argument);
  b.n8 = tracer::Image(3, 2);
  EXPECT_THROW(harness::progressive_reference(a, b, kOrder, harness::ReferenceEstimator::Plain, 1e-2),
               std::invalid_argument);
  EXPECT_EQ(harness::parse_estimator("richardson"), harness::ReferenceEstimator::Richardson);
  EXPECT_THROW(harness::parse_estimator("Plain"), std::invalid_argument);
}

}  // namespace
