#include "harness/sweep_stats.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace harness {

double quantile_sorted(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) throw std::invalid_argument("quantile of no samples");
  const double pos = p * double(sorted.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  const double frac = pos - double(lo);
  return sorted[lo] + (sorted[hi] - sorted[lo]) * frac;
}

TimingStats summarize(const std::vector<double>& samples) {
  std::vector<double> sorted = samples;
  std::sort(sorted.begin(), sorted.end());
  TimingStats s;
  s.samples = samples;
  s.min = sorted.front();
  s.max = sorted.back();
  s.median = quantile_sorted(sorted, 0.5);
  s.q1 = quantile_sorted(sorted, 0.25);
  s.q3 = quantile_sorted(sorted, 0.75);
  return s;
}

void to_json(nlohmann::json& j, const TimingStats& s) {
  j = {{"median", s.median}, {"min", s.min}, {"max", s.max}, {"q1", s.q1},
       {"q3", s.q3},         {"iqr", s.iqr()}, {"samples", s.samples}};
}

}  // namespace harness
