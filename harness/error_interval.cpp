#include "harness/error_interval.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace harness {

Interval seed_spread(double measured, const std::vector<double>& seed_errors) {
  const double inf = std::numeric_limits<double>::infinity();
  if (!std::isfinite(measured)) return {inf, inf};
  Interval out{measured, measured};
  if (seed_errors.size() < 2) return out;
  std::vector<double> finite;
  for (double e : seed_errors)
    if (std::isfinite(e)) finite.push_back(e);
  if (finite.size() < seed_errors.size()) {
    // A broken seed: nothing bounds the error above.
    for (double e : finite) out.lo = std::min(out.lo, e);
    out.hi = inf;
    return out;
  }
  const Interval ci = median_interval(seed_errors);
  return {std::min(ci.lo, measured), std::max(ci.hi, measured)};
}

ErrorInterval error_interval(const Interval& seed, double floor, FrontMetric metric) {
  ErrorInterval out;
  const double f = std::max(floor, 0.0);
  if (metric == FrontMetric::Rmse) {
    out.lo = std::max(0.0, seed.lo - f);
    out.hi = seed.hi + f;
  } else {
    // In the square roots, where the relative MSE is a norm.
    const double lo = std::max(0.0, std::sqrt(std::max(seed.lo, 0.0)) - std::sqrt(f));
    const double hi = std::sqrt(std::max(seed.hi, 0.0)) + std::sqrt(f);
    out.lo = lo * lo;
    out.hi = hi * hi;
  }
  out.resolved = out.lo > f;
  return out;
}

}  // namespace harness
