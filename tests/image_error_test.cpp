// Error metrics (tracer/image_error.h) on synthetic images with known answers.

#include "tracer/image_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace {

using tracer::Image;

Image constant(int w, int h, float v) {
  Image im(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) im.at(x, y) = {v, v, v};
  return im;
}

TEST(ImageError, ConstantOffset) {
  const Image ref = constant(7, 5, 0.5f), img = constant(7, 5, 1.0f);
  const tracer::ImageError e = tracer::image_error(img, ref);
  EXPECT_EQ(e.values, 7u * 5u * 3u);
  EXPECT_DOUBLE_EQ(e.mse, 0.25);
  EXPECT_DOUBLE_EQ(e.rmse, 0.5);
  EXPECT_DOUBLE_EQ(e.mean_bias, 0.5);
  EXPECT_DOUBLE_EQ(e.max_abs, 0.5);
  EXPECT_DOUBLE_EQ(e.epsilon, tracer::kRelMseEpsilon);
  EXPECT_NEAR(e.rel_mse, 0.25 / (0.25 + 0.01), 1e-12);
  // The sign of the bias says which way: too dark is negative.
  EXPECT_DOUBLE_EQ(tracer::image_error(ref, img).mean_bias, -0.5);
}

TEST(ImageError, SymmetricNoiseHasNoBias) {
  // +d and -d on alternating pixels: RMSE d, bias 0; the relative MSE weights a dark reference
  // more than a bright one.
  Image ref(4, 4), img(4, 4);
  const float d = 0.125f;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const float r = x < 2 ? 0.0f : 1.0f;
      ref.at(x, y) = {r, r, r};
      const float s = (x + y) % 2 ? d : -d;
      img.at(x, y) = {r + s, r + s, r + s};
    }
  const tracer::ImageError e = tracer::image_error(img, ref, 0.01);
  EXPECT_DOUBLE_EQ(e.rmse, 0.125);
  EXPECT_DOUBLE_EQ(e.mean_bias, 0.0);
  const double d2 = 0.125 * 0.125;
  EXPECT_NEAR(e.rel_mse, 0.5 * d2 / 0.01 + 0.5 * d2 / 1.01, 1e-12);
  EXPECT_DOUBLE_EQ(e.epsilon, 0.01);
}

TEST(ImageError, IdenticalImagesHaveZeroError) {
  const Image a = constant(3, 3, 0.3f);
  const tracer::ImageError e = tracer::image_error(a, a);
  EXPECT_EQ(e.mse, 0.0);
  EXPECT_EQ(e.rel_mse, 0.0);
  EXPECT_EQ(e.mean_bias, 0.0);
}

TEST(ImageError, NonFiniteRenderIsInfinitelyWrong) {
  const Image ref = constant(2, 2, 0.5f);
  Image img = ref;
  img.at(1, 1).y = std::numeric_limits<float>::quiet_NaN();
  img.at(0, 1).z = std::numeric_limits<float>::infinity();
  const tracer::ImageError e = tracer::image_error(img, ref);
  EXPECT_EQ(e.non_finite, 2u);
  EXPECT_TRUE(std::isinf(e.rmse));
  EXPECT_TRUE(std::isinf(e.rel_mse));
}

TEST(ImageError, BadInputThrows) {
  const Image a = constant(2, 2, 0.5f), b = constant(2, 3, 0.5f);
  EXPECT_THROW(tracer::image_error(a, b), std::invalid_argument);
  EXPECT_THROW(tracer::image_error(Image(), Image()), std::invalid_argument);
  EXPECT_THROW(tracer::image_error(a, a, 0.0), std::invalid_argument);
  Image nan_ref = a;
  nan_ref.at(0, 0).x = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(tracer::image_error(a, nan_ref), std::invalid_argument);
}

TEST(ImageError, MeanImage) {
  const std::vector<Image> ims = {constant(2, 2, 1.0f), constant(2, 2, 2.0f), constant(2, 2, 6.0f)};
  const Image m = tracer::mean_image(ims);
  EXPECT_FLOAT_EQ(m.at(1, 0).x, 3.0f);
  EXPECT_THROW(tracer::mean_image(std::vector<Image>{}), std::invalid_argument);
  tracer::PixelMoments pm;
  pm.add(constant(2, 2, 1.0f));
  EXPECT_THROW(pm.add(constant(3, 2, 1.0f)), std::invalid_argument);
}

TEST(BiasVariance, TwoSeedsExactSplit) {
  // x = r + b +- s: mean r + b, unbiased variance 2 s^2, mse (b^2 + s^2), bias2 = b^2 - s^2.
  const float r = 0.5f, b = 0.25f, s = 0.125f;
  tracer::PixelMoments pm;
  pm.add(constant(3, 2, r + b + s));
  pm.add(constant(3, 2, r + b - s));
  const tracer::BiasVariance bv = tracer::bias_variance(pm, constant(3, 2, r));
  EXPECT_EQ(bv.seeds, 2u);
  EXPECT_DOUBLE_EQ(bv.variance, 2.0 * s * s);
  EXPECT_DOUBLE_EQ(bv.bias2, double(b) * b - double(s) * s);
  EXPECT_DOUBLE_EQ(bv.mse, double(b) * b + double(s) * s);
  EXPECT_DOUBLE_EQ(bv.mean_bias, b);
}

TEST(BiasVariance, RecoversKnownBiasAndNoise) {
  // Gaussian noise of known sigma around r + b, 8 seeds of 64x64x3 values: the estimates land
  // within a few standard errors of b and sigma, and mse is the mean of the per-seed MSEs.
  const int w = 64, h = 64, seeds = 8;
  const double b = 0.02, sigma = 0.1;
  Image ref(w, h);
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<float> level(0.0f, 2.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) ref.at(x, y) = {level(rng), level(rng), level(rng)};
  std::normal_distribution<double> noise(0.0, sigma);
  tracer::PixelMoments pm;
  double mean_mse = 0.0;
  for (int s = 0; s < seeds; ++s) {
    Image im(w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) im.at(x, y)[c] = float(ref.at(x, y)[c] + b + noise(rng));
    pm.add(im);
    mean_mse += tracer::image_error(im, ref).mse / seeds;
  }
  const tracer::BiasVariance bv = tracer::bias_variance(pm, ref);
  EXPECT_NEAR(bv.mse, mean_mse, 1e-9);
  EXPECT_NEAR(bv.noise(), sigma, 0.03 * sigma);
  EXPECT_NEAR(bv.bias(), b, 0.1 * b);
  EXPECT_NEAR(bv.mean_bias, b, 0.1 * b);
  // One seed cannot be split.
  tracer::PixelMoments one;
  one.add(ref);
  EXPECT_THROW(tracer::bias_variance(one, ref), std::invalid_argument);
}

}  // namespace
