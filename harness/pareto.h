#pragma once
// The Pareto front of speed/accuracy points: the points that no other point beats on both time
// and error. A point q dominates p when q is no slower and no less accurate than p and strictly
// better on one of the two. Points with a non-finite or negative time or error (a failed or
// broken render) neither lie on the front nor dominate anything.
//
// Unresolved points (harness/error_interval.h: an error the reference cannot tell from its own)
// dominate only unresolved points: a resolved point leaves the front only on the evidence of
// resolved points. An unresolved error is known only to within an interval that reaches down to
// the reference's floor, so "no less accurate" cannot be certified for it against an error the
// reference does resolve. The alternative, counting an unresolved point's error as the floor,
// was rejected: every resolved error lies above twice the floor, so that would let any no-slower
// unresolved point beat every resolved one, the opposite of not trusting it.

#include <cstddef>
#include <span>
#include <vector>

namespace harness {

/// One measured configuration: how long it took and how wrong it was.
struct TimeError {
  double time = 0.0;   ///< Render time (any unit, the same for every point).
  double error = 0.0;  ///< Error against the reference (any metric, the same for every point).
  /// The error is resolved by the reference (harness/error_interval.h); an unresolved point
  /// dominates only unresolved points.
  bool resolved = true;
};

/// True when `q` dominates `p`: q.time <= p.time, q.error <= p.error, one of them strictly, and
/// q is resolved or p is not.
bool dominates(const TimeError& q, const TimeError& p);

/// Marks the front: out[i] is true when point i is usable and no usable point dominates it.
/// Equal points are all on the front or all off it. O(n log n).
std::vector<bool> pareto_front(std::span<const TimeError> points);

/// The indices of the front's points, fastest first (ties: the more accurate first, then by
/// index). With unresolved points the errors along it need not fall: a resolved point that only
/// unresolved points beat stays on it.
std::vector<std::size_t> pareto_indices(std::span<const TimeError> points);

}  // namespace harness
