#pragma once
// The Pareto front of speed/accuracy points: the points that no other point beats on both time
// and error. A point q dominates p when q is no slower and no less accurate than p and strictly
// better on one of the two. Points with a non-finite or negative time or error (a failed or
// broken render) neither lie on the front nor dominate anything.

#include <cstddef>
#include <span>
#include <vector>

namespace harness {

/// One measured configuration: how long it took and how wrong it was.
struct TimeError {
  double time = 0.0;   ///< Render time (any unit, the same for every point).
  double error = 0.0;  ///< Error against the reference (any metric, the same for every point).
};

/// True when `q` dominates `p`: q.time <= p.time, q.error <= p.error, and one of them strictly.
bool dominates(const TimeError& q, const TimeError& p);

/// Marks the front: out[i] is true when point i is usable and no usable point dominates it.
/// Equal points are all on the front or all off it. O(n log n).
std::vector<bool> pareto_front(std::span<const TimeError> points);

/// The indices of the front's points, fastest first (ties: the more accurate first, then by
/// index).
std::vector<std::size_t> pareto_indices(std::span<const TimeError> points);

}  // namespace harness
