#include "harness/bootstrap.h"

#include "harness/sweep_stats.h"

#include <algorithm>
#include <random>
#include <stdexcept>

namespace harness {
namespace {

/// Interval of `stat` over resamples of the indices 0..n-1.
template <class Stat>
Interval percentile_interval(std::size_t n, double level, int resamples, std::uint64_t seed, Stat stat) {
  if (n == 0) throw std::invalid_argument("bootstrap of no samples");
  std::mt19937_64 rng(seed);
  std::vector<std::size_t> pick(n);
  std::vector<double> stats;
  stats.reserve(std::size_t(resamples));
  for (int b = 0; b < resamples; ++b) {
    // rng() % n: the bias is below n / 2^64, and the draw is the same on every platform.
    for (auto& i : pick) i = std::size_t(rng() % n);
    stats.push_back(stat(pick));
  }
  std::sort(stats.begin(), stats.end());
  const double tail = (1.0 - level) / 2.0;
  return {quantile_sorted(stats, tail), quantile_sorted(stats, 1.0 - tail)};
}

}  // namespace

double median_of(std::vector<double> values) {
  if (values.empty()) throw std::invalid_argument("median of no samples");
  std::sort(values.begin(), values.end());
  return quantile_sorted(values, 0.5);
}

namespace {

std::vector<double> round_ratios(const std::vector<double>& numerator, const std::vector<double>& denominator) {
  if (numerator.size() != denominator.size()) throw std::invalid_argument("unpaired samples");
  std::vector<double> ratios(numerator.size());
  for (std::size_t r = 0; r < ratios.size(); ++r) {
    if (!(denominator[r] > 0.0)) throw std::invalid_argument("a paired ratio's denominator must be > 0");
    ratios[r] = numerator[r] / denominator[r];
  }
  return ratios;
}

}  // namespace

double paired_ratio(const std::vector<double>& numerator, const std::vector<double>& denominator) {
  return median_of(round_ratios(numerator, denominator));
}

Interval paired_ratio_interval(const std::vector<double>& numerator, const std::vector<double>& denominator,
                               double level, int resamples, std::uint64_t seed) {
  // Resampling rounds and taking the median of their ratios is the median's bootstrap over the
  // rounds' ratios.
  return median_interval(round_ratios(numerator, denominator), level, resamples, seed);
}

Interval median_interval(const std::vector<double>& values, double level, int resamples, std::uint64_t seed) {
  std::vector<double> a(values.size());
  return percentile_interval(values.size(), level, resamples, seed, [&](const std::vector<std::size_t>& pick) {
    for (std::size_t k = 0; k < pick.size(); ++k) a[k] = values[pick[k]];
    return median_of(a);
  });
}

}  // namespace harness
