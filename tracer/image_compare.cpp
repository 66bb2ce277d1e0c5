#include "image_compare.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tracer {

namespace {

float max_channel(const Image::Pixel& p) { return std::max(p.x, std::max(p.y, p.z)); }
bool finite(const Image::Pixel& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

}  // namespace

ImageDifference compare_images(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height())
    throw std::invalid_argument("cannot compare a " + std::to_string(a.width()) + "x" +
                                std::to_string(a.height()) + " image with a " +
                                std::to_string(b.width()) + "x" + std::to_string(b.height()) +
                                " one");
  ImageDifference d;
  d.pixels = a.pixels().size();
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < d.pixels; ++i) {
    const Image::Pixel& p = a.pixels()[i];
    const Image::Pixel& q = b.pixels()[i];
    if (!finite(p) || !finite(q)) {
      ++d.non_finite;
      ++d.pixels_off;
      continue;
    }
    float worst = 0.0f;
    for (int c = 0; c < 3; ++c) {
      const double diff = double(p[c]) - double(q[c]);
      sum_sq += diff * diff;
      worst = std::max(worst, float(std::abs(diff)));
    }
    d.max_abs = std::max(d.max_abs, double(worst));
    const float scale = std::max({max_channel(p), max_channel(q), kPixelOffFloor});
    if (worst > kPixelOffFraction * scale) ++d.pixels_off;
  }
  const std::size_t finite_pixels = d.pixels - d.non_finite;
  d.rmse = finite_pixels > 0 ? std::sqrt(sum_sq / (3.0 * double(finite_pixels))) : 0.0;
  d.fraction_off = d.pixels > 0 ? double(d.pixels_off) / double(d.pixels) : 0.0;
  return d;
}

std::size_t count_non_finite(const Image& image) {
  return std::size_t(std::count_if(image.pixels().begin(), image.pixels().end(),
                                   [](const Image::Pixel& p) { return !finite(p); }));
}

}  // namespace tracer
