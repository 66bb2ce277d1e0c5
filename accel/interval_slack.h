#pragma once
// The relative margin every structure widens the ray interval by when it culls a box or a cell.
//
// Node boxes are padded outward at build time, and the interval [tmin, tmax] is widened by this
// margin when a box is tested, so that a primitive whose computed t lies on its box's face (an
// axis-aligned ray through a sphere's centre) or ties the current hit exactly is still visited:
// at a tie the lower id must win whatever the visiting order. With the margin at 0 the oracle
// test reports mismatches in nearly every configuration.

#include "geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace accel {

/// Relative widening of the ray interval for culling: 16 units of roundoff.
inline constexpr float kIntervalSlack = 16.0f * gamma_bound(1);

/// `t` moved up by the slack (a far bound made more generous).
inline float widen_up(float t) { return t + std::abs(t) * kIntervalSlack; }
/// `t` moved down by the slack (a near bound made more generous).
inline float widen_down(float t) { return t - std::abs(t) * kIntervalSlack; }

/// How far a node box spanning [lo, hi] on one axis is moved outward on each side at build
/// time: 4 ulps of its larger coordinate, so that the rounding of the slab test never culls a
/// primitive whose computed hit lies on the box's face.
inline float box_pad(float lo, float hi) {
  return std::max(std::abs(lo), std::abs(hi)) * (4.0f * std::numeric_limits<float>::epsilon());
}

}  // namespace accel
