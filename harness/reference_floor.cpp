#include "harness/reference_floor.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace harness {

namespace {

void require_size(const tracer::Image& image, const tracer::Image& like, const char* what) {
  if (image.width() != like.width() || image.height() != like.height() || image.pixels().empty())
    throw std::invalid_argument(std::string("progressive reference: the ") + what +
                                " image is missing or of another size");
}

/// The standard error of `mean`, the mean of `s` (width x height values), from the spread of the
/// means of the square blocks of `side` pixels a side that cover the image.
double block_standard_error(const std::vector<double>& s, int width, int height, int side, double mean) {
  const int bw = (width + side - 1) / side, bh = (height + side - 1) / side;
  std::vector<double> sum(std::size_t(bw) * std::size_t(bh), 0.0), count(sum.size(), 0.0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t b = std::size_t(y / side) * std::size_t(bw) + std::size_t(x / side);
      sum[b] += s[std::size_t(y) * std::size_t(width) + std::size_t(x)];
      count[b] += 1.0;
    }
  const double blocks = double(sum.size());
  if (sum.size() < 2) return 0.0;
  double var = 0.0;  // of the block means
  for (std::size_t b = 0; b < sum.size(); ++b) {
    const double m = sum[b] / count[b];
    var += (m - mean) * (m - mean);
  }
  return std::sqrt(var / (blocks - 1.0) / blocks);
}

/// How many blocks of `side` pixels cover a width x height image.
int blocks_of(int side, int width, int height) {
  return ((width + side - 1) / side) * ((height + side - 1) / side);
}

}  // namespace

MeanEstimate block_mean_upper(const std::vector<double>& s, int width, int height) {
  if (width <= 0 || height <= 0 || s.size() != std::size_t(width) * std::size_t(height))
    throw std::invalid_argument("block_mean_upper: the values do not fill a width x height image");
  double mean = 0.0;
  for (double v : s) mean += v;
  mean /= double(s.size());
  // Blocking (Flyvbjerg and Petersen 1989): the block means' standard error grows with the block
  // while blocks are smaller than the values' correlation length, then levels off; the largest
  // over sides 8, 16, 32, ... (while 16 blocks remain) is the one that does not understate it.
  // Images too small for 16 blocks of 8 use the largest side that gives 16.
  int side = 8;
  while (side > 1 && blocks_of(side, width, height) < kMinBlocks) side /= 2;
  double se = block_standard_error(s, width, height, side, mean);
  for (int larger = side * 2; blocks_of(larger, width, height) >= kMinBlocks; larger *= 2)
    se = std::max(se, block_standard_error(s, width, height, larger, mean));
  const double value = std::max(0.0, mean) / 3.0;  // per channel value: each pixel's sum holds three
  return {value, value + 1.96 * se / 3.0};
}

const char* estimator_name(ReferenceEstimator e) {
  return e == ReferenceEstimator::Plain ? "plain" : "richardson";
}

ReferenceEstimator parse_estimator(const std::string& name) {
  if (name == "plain") return ReferenceEstimator::Plain;
  if (name == "richardson") return ReferenceEstimator::Richardson;
  throw std::invalid_argument("estimator must be plain or richardson, got '" + name + "'");
}

int estimator_depth(ReferenceEstimator e) { return e == ReferenceEstimator::Plain ? 1 : 2; }

long long estimator_divisor(ReferenceEstimator e) {
  long long d = 1;
  for (int i = 0; i < estimator_depth(e); ++i) d *= kStageRatio;
  return d;
}

ProgressiveReference progressive_reference(const HalfStages& a, const HalfStages& b, double order,
                                           ReferenceEstimator e, double epsilon) {
  if (!(order > 0.0) || !std::isfinite(order))
    throw std::invalid_argument("progressive reference: the bias order must be > 0");
  const bool richardson = e == ReferenceEstimator::Richardson;
  for (const HalfStages* h : {&a, &b}) {
    require_size(h->n, a.n, "N-stage");
    require_size(h->n8, a.n, "N/8-stage");
    if (richardson) require_size(h->n64, a.n, "N/64-stage");
  }
  const double g = std::pow(double(kStageRatio), order);
  // The estimate of one half at N (now) and one checkpoint earlier (then), per channel value.
  const auto now = [&](const HalfStages& h, std::size_t i, int c) {
    const double n = h.n.pixels()[i][c], n8 = h.n8.pixels()[i][c];
    return richardson ? (g * n - n8) / (g - 1.0) : n;
  };
  const auto then = [&](const HalfStages& h, std::size_t i, int c) {
    const double n8 = h.n8.pixels()[i][c];
    return richardson ? (g * n8 - double(h.n64.pixels()[i][c])) / (g - 1.0) : n8;
  };

  // The plain estimator measures how fast its bias falls where the N/64 stage is there too:
  // the bias/variance split of the stage before (L_N/8 - L_N/64) against this one's.
  const bool measure_rate = !richardson && [&] {
    for (const HalfStages* h : {&a, &b})
      if (h->n64.width() != a.n.width() || h->n64.height() != a.n.height() || h->n64.pixels().empty()) return false;
    return true;
  }();

  const std::size_t pixels = a.n.pixels().size();
  ProgressiveReference out;
  out.image = tracer::Image(a.n.width(), a.n.height());
  // Per pixel, summed over its channels: the bias^2 split of this stage's difference D and of
  // the one before (not yet divided by (g - 1)^2); this stage's also weighted.
  std::vector<double> bias(pixels), bias_rel(pixels), before(pixels, 0.0);
  const auto split = [](double da, double db) {
    const double dbar = 0.5 * (da + db);
    return dbar * dbar - 0.25 * (da - db) * (da - db);
  };
  double noise = 0.0, noise_rel = 0.0;
  for (std::size_t i = 0; i < pixels; ++i) {
    double pixel_bias = 0.0, pixel_bias_rel = 0.0, pixel_before = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double xa = now(a, i, c), xb = now(b, i, c);
      const double r = 0.5 * (xa + xb);
      out.image.at(int(i % std::size_t(a.n.width())), int(i / std::size_t(a.n.width())))[c] = float(r);
      const double w = 1.0 / (r * r + epsilon);
      const double n2 = 0.25 * (xa - xb) * (xa - xb);
      const double b2 = split(xa - then(a, i, c), xb - then(b, i, c));
      noise += n2;
      noise_rel += w * n2;
      pixel_bias += b2;
      pixel_bias_rel += w * b2;
      if (measure_rate)
        pixel_before += split(a.n8.pixels()[i][c] - a.n64.pixels()[i][c], b.n8.pixels()[i][c] - b.n64.pixels()[i][c]);
    }
    bias[i] = pixel_bias;
    bias_rel[i] = pixel_bias_rel;
    before[i] = pixel_before;
  }
  const double values = 3.0 * double(pixels);
  out.noise_mse = noise / values;
  out.noise_rel = noise_rel / values;
  const int w = a.n.width(), h = a.n.height();
  const MeanEstimate now_split = block_mean_upper(bias, w, h);
  // g as measured: the ratio of the two stages' bias (RMS), where both are clearly there (above
  // 1.96 standard errors). It may only lower g below the theory's (a bias falling more slowly
  // makes the same difference D stand for a larger bias), never raise it, and not below sqrt(g),
  // the order of the blur at a discontinuity (the top of reference_floor.h).
  double ratio = g;
  if (measure_rate) {
    const MeanEstimate before_split = block_mean_upper(before, w, h);
    const auto clear = [](const MeanEstimate& m) { return m.value > 0.0 && m.value > m.upper - m.value; };
    if (clear(now_split) && clear(before_split))
      ratio = std::clamp(std::sqrt(before_split.value / now_split.value), std::sqrt(g), g);
  }
  const double scale = 1.0 / ((ratio - 1.0) * (ratio - 1.0));
  const MeanEstimate rel_split = block_mean_upper(bias_rel, w, h);
  out.bias_mse = {now_split.value * scale, now_split.upper * scale};
  out.bias_rel = {rel_split.value * scale, rel_split.upper * scale};
  out.bias_order = std::log(ratio) / std::log(double(kStageRatio));
  return out;
}

}  // namespace harness
