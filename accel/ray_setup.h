#pragma once
// Kay–Kajiya per-ray precomputation and the slab test.

#include "geometry.h"

#include <cmath>
#include <utility>

namespace accel {

/// Everything the slab test needs that depends only on the ray, computed once per ray.
struct RaySetup {
  Vec3 org;       ///< Ray origin.
  Vec3 inv_dir;   ///< 1 / dir per component; +-inf for a +-0 component.
  int neg[3];     ///< 1 where the direction component is negative (sign bit set, so -0 counts).

  // Inlined: once per ray, and its divisions overlap the first node test only when inlined.
  [[gnu::always_inline]] explicit RaySetup(const Ray& ray)
      : org(ray.org), inv_dir(1.0f / ray.dir.x, 1.0f / ray.dir.y, 1.0f / ray.dir.z) {
    neg[0] = std::signbit(ray.dir.x);
    neg[1] = std::signbit(ray.dir.y);
    neg[2] = std::signbit(ray.dir.z);
  }
  /// Direction octant, 0..7 (bit k set when component k is negative).
  int octant() const { return neg[0] | (neg[1] << 1) | (neg[2] << 2); }
};

/// Scale for the far slab distance that makes the test conservative under rounding (Ize 2013).
inline constexpr float kSlabFarScale = 1.0f + 2.0f * gamma_bound(3);

/// Clips [t0, t1] to the box. Returns false when the interval becomes empty.
/// A 0 * inf = NaN slab distance (ray parallel to and exactly on a face) leaves the interval
/// unchanged, whatever the sign of the zero: the comparisons are written so NaN loses.
inline bool slab_clip(const Aabb& box, const RaySetup& r, float& t0, float& t1) {
  for (int a = 0; a < 3; ++a) {
    const float lo = box.lo[a], hi = box.hi[a];
    float t_near = (lo - r.org[a]) * r.inv_dir[a];
    float t_far = (hi - r.org[a]) * r.inv_dir[a];
    if (r.neg[a]) std::swap(t_near, t_far);
    t_far *= kSlabFarScale;
    t0 = t_near > t0 ? t_near : t0;
    t1 = t_far < t1 ? t_far : t1;
  }
  return t0 <= t1;
}

}  // namespace accel
