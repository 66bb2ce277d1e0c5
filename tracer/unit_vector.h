#pragma once
// Normalising a direction read from a file, whatever its magnitude.

#include "scene_geometry.h"

#include <algorithm>
#include <cmath>

namespace tracer {

/// The unit vector along `v`, or zero when `v` is zero or not finite. Scales by the largest
/// component first, so that neither a huge vector (whose squared length overflows, as
/// [1e30, 0, 0] does) nor a tiny one (whose squared length underflows) collapses to zero.
inline Vec3 unit_vector(const Vec3& v) {
  const float m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (!(m > 0.0f) || !std::isfinite(m)) return Vec3(0.0f);
  const Vec3 s = v / m;
  return s / std::sqrt(s.x * s.x + s.y * s.y + s.z * s.z);
}

}  // namespace tracer
