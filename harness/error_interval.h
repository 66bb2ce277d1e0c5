#pragma once
// The interval of a front point's error (docs/accuracy.md, "Intervals and unresolved points").
//
// A point's error is measured once, on the timed render's seed, against a reference that is
// itself wrong by about its floor F (harness/accuracy_reference.h ReferenceFloor). Two things
// make the error uncertain, and they combine as follows:
//
// - Seed noise: another seed gives another image and another error. The spread of the errors
//   of the point's seeds (the timed one and the --seeds extra ones) is [a, b] (seed_spread);
//   a point without seed renders (a deterministic reference, or an image no seed changes) has
//   a = b = its error.
// - The reference: every error is measured against the reference R, not the truth T. RMSE is a
//   norm of the difference, so by the triangle inequality
//       |RMSE(x, R) - RMSE(x, T)| <= RMSE(R, T) = F,
//   whatever the correlation of the two errors, and the error against the truth lies in
//   [max(0, a - F), b + F]. The floor adds linearly, not in quadrature: quadrature,
//   RMSE(x, T)^2 = RMSE(x, R)^2 - F^2, holds only on average and only when the point's error and
//   the reference's are uncorrelated, which truncation is not (depth 8 and depth 64 both miss
//   the light past bounce 64, with the same sign).
// - The relative MSE is a squared norm, mean w (x - r)^2 with w = 1 / (r^2 + eps) the
//   reference's weights: its square root is a (weighted) norm and obeys the same inequality, so
//   its floor adds to the square roots: [max(0, sqrt(a) - sqrt(F))^2, (sqrt(b) + sqrt(F))^2],
//   F the floor's relative MSE. (Weighted by the reference's brightness, as the metric is.)
//
// A point is resolved when its interval's lower end lies above the floor: its error is then
// known to exceed the reference's own. Otherwise the reference cannot tell the point from
// itself (an error at or below twice the floor in RMSE, four times in relative MSE, before
// seed noise), and the point is unresolved.

#include "harness/bootstrap.h"
#include "harness/front_metric.h"

#include <vector>

namespace harness {

/// What is known of a front point's error against the truth, in the front's metric.
struct ErrorInterval {
  double lo = 0.0;        ///< Smallest error the point may have against the truth (>= 0).
  double hi = 0.0;        ///< Largest error it may have (infinite for a broken render).
  bool resolved = false;  ///< lo lies above the floor: the error is more than the reference's.
};

/// The spread of a point's measured error over its seeds: the 95% percentile-bootstrap interval
/// of the median of `seed_errors` (harness/bootstrap.h median_interval; for up to five seeds,
/// their smallest and largest), widened to hold `measured`, the timed render's error, which is
/// the point drawn. [measured, measured] with fewer than two seed errors. A non-finite error
/// makes the upper end infinite.
Interval seed_spread(double measured, const std::vector<double>& seed_errors);

/// The interval of the error against the truth of a point whose measured errors spread over
/// `seed`, measured against a reference with floor `floor` (both in `metric`), and whether it
/// is resolved (see the top of this file).
ErrorInterval error_interval(const Interval& seed, double floor, FrontMetric metric);

}  // namespace harness
