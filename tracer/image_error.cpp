#include "image_error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tracer {

namespace {

std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

void check_same_size(const Image& a, const Image& b, const char* what) {
  if (a.width() != b.width() || a.height() != b.height())
    throw std::invalid_argument(std::string(what) + ": image is " + size_text(a.width(), a.height()) +
                                ", reference is " + size_text(b.width(), b.height()));
  if (a.pixels().empty()) throw std::invalid_argument(std::string(what) + ": empty image");
}

void check_finite_reference(const Image& reference) {
  for (const Image::Pixel& p : reference.pixels())
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(p[c]))
        throw std::invalid_argument("reference image has a non-finite value");
}

}  // namespace

ImageError image_error(const Image& image, const Image& reference, double epsilon) {
  check_same_size(image, reference, "image_error");
  if (!(epsilon > 0.0) || !std::isfinite(epsilon))
    throw std::invalid_argument("image_error: epsilon must be > 0, got " + std::to_string(epsilon));
  check_finite_reference(reference);
  ImageError e;
  e.epsilon = epsilon;
  double sum2 = 0.0, rel = 0.0, bias = 0.0, max_abs = 0.0;
  const auto& xs = image.pixels();
  const auto& rs = reference.pixels();
  for (std::size_t i = 0; i < xs.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double x = xs[i][c], r = rs[i][c];
      if (!std::isfinite(x)) {
        e.non_finite++;
        continue;
      }
      const double d = x - r;
      sum2 += d * d;
      rel += d * d / (r * r + epsilon);
      bias += d;
      max_abs = std::max(max_abs, std::abs(d));
    }
  e.values = xs.size() * 3;
  const double n = double(e.values);
  if (e.non_finite) {
    const double inf = std::numeric_limits<double>::infinity();
    e.mse = e.rmse = e.rel_mse = e.max_abs = e.mean_bias = inf;
    return e;
  }
  e.mse = sum2 / n;
  e.rmse = std::sqrt(e.mse);
  e.rel_mse = rel / n;
  e.mean_bias = bias / n;
  e.max_abs = max_abs;
  return e;
}

void PixelMoments::add(const Image& image) {
  if (count_ == 0) {
    if (image.pixels().empty()) throw std::invalid_argument("PixelMoments: empty image");
    width_ = image.width();
    height_ = image.height();
    mean_.assign(image.pixels().size() * 3, 0.0);
    m2_.assign(mean_.size(), 0.0);
  } else if (image.width() != width_ || image.height() != height_) {
    throw std::invalid_argument("PixelMoments: image is " + size_text(image.width(), image.height()) +
                                ", the first was " + size_text(width_, height_));
  }
  count_++;
  const double n = double(count_);
  const auto& px = image.pixels();
  for (std::size_t i = 0; i < px.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const std::size_t k = 3 * i + std::size_t(c);
      const double x = px[i][c];
      if (!std::isfinite(x)) non_finite_++;
      const double d = x - mean_[k];
      mean_[k] += d / n;
      m2_[k] += d * (x - mean_[k]);
    }
}

Image PixelMoments::mean() const {
  if (count_ == 0) throw std::invalid_argument("PixelMoments: no image added");
  Image out(width_, height_);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(width_) + std::size_t(x);
      out.at(x, y) = {float(mean_[3 * i]), float(mean_[3 * i + 1]), float(mean_[3 * i + 2])};
    }
  return out;
}

Image mean_image(std::span<const Image> images) {
  PixelMoments m;
  for (const Image& im : images) m.add(im);
  return m.mean();
}

double BiasVariance::bias() const { return std::sqrt(std::max(bias2, 0.0)); }
double BiasVariance::noise() const { return std::sqrt(std::max(variance, 0.0)); }

BiasVariance bias_variance(const PixelMoments& moments, const Image& reference) {
  if (moments.count() < 2)
    throw std::invalid_argument("bias_variance: needs at least two seeds, got " +
                                std::to_string(moments.count()));
  if (reference.width() != moments.width() || reference.height() != moments.height())
    throw std::invalid_argument("bias_variance: images are " + size_text(moments.width(), moments.height()) +
                                ", reference is " + size_text(reference.width(), reference.height()));
  check_finite_reference(reference);
  const double s = double(moments.count());
  const auto& mean = moments.means();
  const auto& m2 = moments.m2();
  const auto& rs = reference.pixels();
  double sq = 0.0, var = 0.0, bias = 0.0;
  for (std::size_t i = 0; i < rs.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const std::size_t k = 3 * i + std::size_t(c);
      const double d = mean[k] - double(rs[i][c]);
      sq += d * d;
      bias += d;
      var += m2[k] / (s - 1.0);
    }
  const double n = double(mean.size());
  BiasVariance out;
  out.seeds = moments.count();
  if (moments.non_finite()) {
    const double inf = std::numeric_limits<double>::infinity();
    out.mse = out.variance = out.bias2 = out.mean_bias = inf;
    return out;
  }
  out.variance = var / n;
  out.bias2 = sq / n - out.variance / s;
  out.mse = out.bias2 + out.variance;
  out.mean_bias = bias / n;
  return out;
}

}  // namespace tracer
