#pragma once
// How far a rendered image is from a reference image: the accuracy metrics of speed/accuracy
// fronts (docs/accuracy.md). Every metric is over every channel of every pixel, in double.
//
//   RMSE          sqrt(mean (x - r)^2)                        radiance units
//   relative MSE  mean (x - r)^2 / (r^2 + eps)                dimensionless, eps stated
//   mean bias     mean (x - r)                                radiance units (signed)
//
// For stochastic renders, PixelMoments gathers the images of several seeds and bias_variance()
// splits their mean squared error into squared bias and variance.

#include "image.h"

#include <cstddef>
#include <span>
#include <vector>

namespace tracer {

/// Default eps of the relative MSE, radiance units squared: pixels darker than about 0.1 are
/// weighted as if they were 0.1 bright, so black pixels do not dominate. Every report states it.
inline constexpr double kRelMseEpsilon = 1e-2;

/// The error of one image against a reference.
struct ImageError {
  std::size_t values = 0;      ///< Channel values compared (3 per pixel).
  std::size_t non_finite = 0;  ///< Channel values of the image that are NaN or infinite.
  double mse = 0.0;            ///< Mean squared error, radiance units squared.
  double rmse = 0.0;           ///< Root mean squared error, radiance units.
  double rel_mse = 0.0;        ///< Mean of (x - r)^2 / (r^2 + epsilon), dimensionless.
  double epsilon = kRelMseEpsilon;  ///< The eps of rel_mse, radiance units squared.
  double mean_bias = 0.0;      ///< Mean of x - r, radiance units (negative: too dark).
  double max_abs = 0.0;        ///< Largest |x - r|, radiance units.
};

/// The error of `image` against `reference`. Throws std::invalid_argument when the sizes differ,
/// when an image is empty, when epsilon is not > 0, or when the reference has a non-finite value.
/// A non-finite value in `image` is counted and makes mse, rmse, rel_mse, mean_bias and max_abs
/// infinite: a broken render is never close to anything.
ImageError image_error(const Image& image, const Image& reference, double epsilon = kRelMseEpsilon);

/// Per-pixel running mean and variance (Welford, in double) of images of one size.
class PixelMoments {
 public:
  /// Adds an image; the first one fixes the size (std::invalid_argument on another size later).
  void add(const Image& image);
  std::size_t count() const { return count_; }  ///< Images added.
  /// Channel values added that were NaN or infinite (they make the moments non-finite).
  std::size_t non_finite() const { return non_finite_; }
  int width() const { return width_; }          ///< Pixels.
  int height() const { return height_; }        ///< Pixels.
  /// The per-pixel mean of the images added (at least one).
  Image mean() const;
  /// Per channel value: the running mean and the sum of squared deviations (Welford's M2).
  const std::vector<double>& means() const { return mean_; }
  const std::vector<double>& m2() const { return m2_; }

 private:
  std::size_t count_ = 0;
  std::size_t non_finite_ = 0;
  int width_ = 0, height_ = 0;
  std::vector<double> mean_, m2_;
};

/// The per-pixel mean of `images` (at least one, all one size): the mean-image helper.
Image mean_image(std::span<const Image> images);

/// The split of the mean squared error of a stochastic render over its seeds:
/// mse = bias2 + variance, where for one render X at a pixel value, E[(X - r)^2] =
/// (E[X] - r)^2 + Var[X]. Averaged over every channel value.
struct BiasVariance {
  std::size_t seeds = 0;   ///< Renders (seeds) the split is over.
  double mse = 0.0;        ///< Mean over seeds of each render's MSE, radiance units squared.
  double variance = 0.0;   ///< Unbiased per-value variance across seeds, averaged; units squared.
  /// Squared bias: mean (mean over seeds - r)^2 - variance / seeds, an unbiased estimate (it can
  /// come out slightly negative when the bias is far below the noise); units squared.
  double bias2 = 0.0;
  double bias() const;   ///< sqrt(max(bias2, 0)), radiance units.
  double noise() const;  ///< sqrt(variance): one render's RMS deviation from its mean, units.
  double mean_bias = 0.0;  ///< Mean of (mean over seeds - r): signed bias, radiance units.
};

/// Splits the error of the images gathered in `moments` (at least two) against `reference`.
/// Throws std::invalid_argument on fewer than two images or another size. A non-finite value
/// among the images makes every figure infinite.
BiasVariance bias_variance(const PixelMoments& moments, const Image& reference);

}  // namespace tracer
