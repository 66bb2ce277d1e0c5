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
#include "scalar.h"
#include "surface.h"

#include "accel/geometry.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <type_traits>

namespace tracer {

/// The point p, whose error bound is p_error, moved off its surface (unit geometric normal n)
/// to the side that `w` points to (dot(w, n) > 0: the side n faces, else the other side).
/// A ray started there with tmin = 0 leaves the surface on that side.
///
/// p moves by d = sum |n_i| p_error_i along the normal, rounded to nearest; where that rounding
/// left the move along the normal at or below d (measured exactly, in a wider type), the
/// coordinate whose ulp reaches furthest along the normal steps one ulp further, until it is
/// above d.
/// That is the least move on the grid of representable points that clears the bound: stepping
/// every coordinate an ulp (pbrt's rounding) moves up to sqrt(3) ulps along the normal, and each
/// such bias compounds along a path (a ray reflecting inside a sphere drifts inward).
template <class T>
Vec3T<T> offset_ray_origin(const Vec3T<T>& p, const Vec3T<T>& p_error, const Vec3T<T>& n,
                           const Vec3T<T>& w) {
  using Wide = std::conditional_t<std::is_same_v<T, float>, double, long double>;
  const T d = glm::dot(glm::abs(n), p_error);
  const Vec3T<T> side = glm::dot(w, n) > T(0) ? n : -n;
  Vec3T<T> po = p + d * side;
  // The coordinate whose ulp moves furthest along the normal: the deficit left by rounding is
  // under 1.5 of its steps, so the loop ends after two at most.
  int k = 0;
  T best = T(-1);
  for (int i = 0; i < 3; ++i) {
    const T reach = std::abs(side[i]) * (next_up(std::abs(po[i])) - std::abs(po[i]));
    if (reach > best) best = reach, k = i;
  }
  for (int step = 0; step < 8; ++step) {
    Wide along = 0, moved = 0;
    for (int i = 0; i < 3; ++i) {
      const Wide m = Wide(po[i]) - Wide(p[i]);  // exact for float in double
      along += m * Wide(side[i]);
      moved += m < 0 ? -m : m;
    }
    // Clear d by a hair more than the rounding of `along` and the normal's few-ulp tilt.
    if (along > Wide(d) + Wide(0x1p-20) * moved) break;
    po[k] = side[k] > T(0) ? next_up(po[k]) : next_down(po[k]);
  }
  return po;
}

/// The origin of a ray leaving `sp` to the side that `w` points to (see above).
template <class T>
Vec3T<T> offset_ray_origin(const SurfacePointT<T>& sp, const Vec3T<T>& w) {
  return offset_ray_origin(sp.p, sp.p_error, sp.n_geo, w);
}

/// A ray of direction `dir` leaving `sp` on the side `dir` points to, tmin = 0, tmax = inf.
template <class T>
RayT<T> spawn_ray(const SurfacePointT<T>& sp, const Vec3T<T>& dir) {
  RayT<T> r;
  r.org = offset_ray_origin(sp, dir);
  r.dir = dir;
  return r;
}

/// The segment from `origin` (already off its surface) towards `target`, whose error bound is
/// `target_error`: dir = target - origin, so t = 1 at the target, and tmax is 1 shortened by
/// the target's bound and the rounding of dir and of org + t dir (3 ulps of |dir|), so that the
/// surface a target lies on never blocks the segment.
template <class T>
RayT<T> segment_to(const Vec3T<T>& origin, const Vec3T<T>& target,
                   const Vec3T<T>& target_error = Vec3T<T>(T(0))) {
  RayT<T> r;
  r.org = origin;
  r.dir = target - origin;
  const T len = glm::length(r.dir);
  const T shorten = rounding_gamma<T>(3) + glm::length(target_error) / len;
  r.tmax = len > T(0) ? next_down(T(1) - shorten) : T(0);
  return r;
}

/// A shadow ray from `sp` to the point `target`: leaves on the target's side, ends short of it.
template <class T>
RayT<T> spawn_ray_to(const SurfacePointT<T>& sp, const Vec3T<T>& target,
                     const Vec3T<T>& target_error = Vec3T<T>(T(0))) {
  return segment_to(offset_ray_origin(sp, target - sp.p), target, target_error);
}

}  // namespace tracer
