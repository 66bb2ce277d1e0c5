#include "harness/pareto.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace harness {

namespace {

bool usable(const TimeError& p) {
  return std::isfinite(p.time) && std::isfinite(p.error) && p.time >= 0.0 && p.error >= 0.0;
}

/// Usable points' indices by time, then error, then index.
std::vector<std::size_t> sorted_usable(std::span<const TimeError> points) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (usable(points[i])) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (points[a].time != points[b].time) return points[a].time < points[b].time;
    if (points[a].error != points[b].error) return points[a].error < points[b].error;
    return a < b;
  });
  return order;
}

}  // namespace

bool dominates(const TimeError& q, const TimeError& p) {
  if (!usable(q) || !usable(p)) return false;
  if (!q.resolved && p.resolved) return false;
  return q.time <= p.time && q.error <= p.error && (q.time < p.time || q.error < p.error);
}

namespace {

/// Marks in `on` the points of `order` (usable indices sorted as by sorted_usable) whose
/// resolved flag is `resolved` and that no point of `order` beats on time and error.
void mark_front(std::span<const TimeError> points, const std::vector<std::size_t>& order, bool resolved,
                std::vector<bool>& on) {
  // Sweep by time. `best` is the smallest error among strictly faster points; within a group of
  // equal times only the smallest error can be on the front, and only if it beats `best`.
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t g = 0; g < order.size();) {
    std::size_t end = g;
    while (end < order.size() && points[order[end]].time == points[order[g]].time) ++end;
    const double group_min = points[order[g]].error;  // sorted by error within the group
    if (group_min < best)
      for (std::size_t k = g; k < end && points[order[k]].error == group_min; ++k)
        if (points[order[k]].resolved == resolved) on[order[k]] = true;
    best = std::min(best, group_min);
    g = end;
  }
}

}  // namespace

std::vector<bool> pareto_front(std::span<const TimeError> points) {
  std::vector<bool> on(points.size(), false);
  const std::vector<std::size_t> order = sorted_usable(points);
  // An unresolved point may be dominated by any point: the front of all of them decides it. A
  // resolved point may be dominated only by resolved ones: the front of those alone decides it.
  mark_front(points, order, false, on);
  std::vector<std::size_t> resolved;
  for (std::size_t i : order)
    if (points[i].resolved) resolved.push_back(i);
  mark_front(points, resolved, true, on);
  return on;
}

std::vector<std::size_t> pareto_indices(std::span<const TimeError> points) {
  const std::vector<bool> on = pareto_front(points);
  std::vector<std::size_t> out;
  for (std::size_t i : sorted_usable(points))
    if (on[i]) out.push_back(i);
  return out;
}

}  // namespace harness
