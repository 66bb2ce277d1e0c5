#pragma once
// Summary statistics of repeated timings: the median and its spread.

#include <nlohmann/json.hpp>

#include <vector>

namespace harness {

/// Order statistics of a set of timings, all in milliseconds.
struct TimingStats {
  double median = 0.0;          ///< Median, ms.
  double min = 0.0;             ///< Fastest sample, ms.
  double max = 0.0;             ///< Slowest sample, ms.
  double q1 = 0.0;              ///< First quartile (linear interpolation), ms.
  double q3 = 0.0;              ///< Third quartile (linear interpolation), ms.
  std::vector<double> samples;  ///< Every sample in measurement order, ms.

  /// Interquartile range q3 - q1, ms.
  double iqr() const { return q3 - q1; }
};

/// Quantile p in [0, 1] of sorted values by linear interpolation between closest ranks
/// (Hyndman & Fan type 7, numpy's default). Requires a non-empty input.
double quantile_sorted(const std::vector<double>& sorted, double p);

/// Summarises samples (at least one).
TimingStats summarize(const std::vector<double>& samples);

void to_json(nlohmann::json& j, const TimingStats& s);

}  // namespace harness
