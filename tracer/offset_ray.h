#pragma once
// Rays leaving a surface: the one API every ray spawner uses (Whitted, SPD, photon tracing).
//
// A secondary ray starts at its surface point moved along the geometric normal by exactly the
// point's error bound projected on the normal, sum |n_i| p_error_i, and then one more ulp per
// coordinate away from the surface, so that rounding the moved point cannot bring it back
// (pbrt-v4, Pharr, Jakob and Humphreys, ch. 6.8.6). The origin is then on the chosen side of the
// exact surface, and no further: a fixed epsilon (1e-4 is below one ulp at 1e5) or a fixed
// number of ulps per coordinate (256 ulps is 2 units at 1e5) either re-hits the surface or jumps
// over its neighbours. A ray towards a point (a shadow ray towards a light) ends short of the
// point by the rounding of its own direction and the target's error bound.

#include "rounding.h"
#include "surface.h"

#include "accel/geometry.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace tracer {

/// The point p, whose error bound is p_error, moved off its surface (unit geometric normal n)
/// to the side that `w` points to (dot(w, n) > 0: the side n faces, else the other side).
/// A ray started there with tmin = 0 leaves the surface on that side.
template <class T>
glm::vec<3, T> offset_ray_origin(const glm::vec<3, T>& p, const glm::vec<3, T>& p_error,
                                 const glm::vec<3, T>& n, const glm::vec<3, T>& w) {
  const T d = glm::dot(glm::abs(n), p_error);
  const glm::vec<3, T> side = glm::dot(w, n) > T(0) ? n : -n;
  glm::vec<3, T> po = p + d * side;
  for (int i = 0; i < 3; ++i) {
    if (side[i] > T(0))
      po[i] = next_up(po[i]);
    else if (side[i] < T(0))
      po[i] = next_down(po[i]);
  }
  return po;
}

/// The origin of a ray leaving `sp` to the side that `w` points to (see above).
inline Vec3 offset_ray_origin(const SurfacePoint& sp, const Vec3& w) {
  return offset_ray_origin(sp.p, sp.p_error, sp.n_geo, w);
}

/// A ray of direction `dir` leaving `sp` on the side `dir` points to, tmin = 0, tmax = inf.
inline Ray spawn_ray(const SurfacePoint& sp, const Vec3& dir) {
  Ray r;
  r.org = offset_ray_origin(sp, dir);
  r.dir = dir;
  return r;
}

/// The segment from `origin` (already off its surface) towards `target`, whose error bound is
/// `target_error`: dir = target - origin, so t = 1 at the target, and tmax is 1 shortened by
/// the target's bound and the rounding of dir and of org + t dir (3 ulps of |dir|), so that the
/// surface a target lies on never blocks the segment.
inline Ray segment_to(const Vec3& origin, const Vec3& target, const Vec3& target_error = Vec3(0.0f)) {
  Ray r;
  r.org = origin;
  r.dir = target - origin;
  const float len = glm::length(r.dir);
  const float shorten = rounding_gamma<float>(3) + glm::length(target_error) / len;
  r.tmax = len > 0.0f ? next_down(1.0f - shorten) : 0.0f;
  return r;
}

/// A shadow ray from `sp` to the point `target`: leaves on the target's side, ends short of it.
inline Ray spawn_ray_to(const SurfacePoint& sp, const Vec3& target,
                        const Vec3& target_error = Vec3(0.0f)) {
  return segment_to(offset_ray_origin(sp, target - sp.p), target, target_error);
}

}  // namespace tracer
