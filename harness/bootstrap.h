#pragma once
// Bootstrap confidence intervals for timings measured in interleaved rounds.
//
// Samples are paired by round: in round r every configuration (naive included) rendered once,
// close together in time, so a machine's drift moves all of round r's samples alike. Resampling
// whole rounds (not samples independently) keeps that pairing, and the interval of the paired
// ratio (the median of the rounds' ratios) then reflects the noise that the interleaving did
// not cancel. Percentile bootstrap
// (Efron & Tibshirani, "An Introduction to the Bootstrap", 1993, ch. 13), with a fixed seed so
// that the same samples always give the same interval.

#include <cstdint>
#include <vector>

namespace harness {

/// A two-sided interval [lo, hi].
struct Interval {
  double lo = 0.0;  ///< Lower bound.
  double hi = 0.0;  ///< Upper bound.

  /// hi - lo relative to `centre` (0 when centre is 0).
  double relative_width(double centre) const { return centre != 0.0 ? (hi - lo) / centre : 0.0; }
};

/// Resamples drawn per interval.
inline constexpr int kBootstrapResamples = 2000;

/// Median of `values` (at least one; linear interpolation between the middle two when even).
double median_of(std::vector<double> values);

/// The paired ratio of two contenders timed in the same rounds: the median over rounds r of
/// numerator[r] / denominator[r]. Each round is a block: a slowdown of the machine that lasts
/// the round moves both of its samples and cancels in its ratio, where a ratio of the two
/// medians lets it through whenever the slow rounds are not the same share of each median.
/// Both vectors have the same length, at least one, and a denominator is > 0.
double paired_ratio(const std::vector<double>& numerator, const std::vector<double>& denominator);

/// 95% (or `level`) percentile-bootstrap interval of paired_ratio(numerator, denominator),
/// resampling the rounds with replacement.
Interval paired_ratio_interval(const std::vector<double>& numerator, const std::vector<double>& denominator,
                               double level = 0.95, int resamples = kBootstrapResamples,
                               std::uint64_t seed = 0x5eed);

/// 95% (or `level`) percentile-bootstrap interval of the median of `values` (at least one).
Interval median_interval(const std::vector<double>& values, double level = 0.95, int resamples = kBootstrapResamples,
                         std::uint64_t seed = 0x5eed);

}  // namespace harness
