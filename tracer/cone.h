#pragma once
// Truncated cone or cylinder without end caps (NFF's `c` primitive).
//
// The surface is every point whose distance from the axis segment [base, base + height * axis]
// equals the radius interpolated linearly from base_radius to apex_radius. The quadratic is
// solved in double precision from the ray's components perpendicular to the axis, so rays along
// the axis and grazing rays stay exact (a float solve loses the root near a tangent).

#include "scalar.h"

#include "accel/geometry.h"

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <utility>

namespace tracer {

using accel::Ray;
using accel::Vec3;

struct Cone {
  Vec3 base{0.0f};                  ///< Centre of the base end, world units.
  float base_radius = 1.0f;         ///< Radius at the base, world units; < 0: inside visible.
  Vec3 axis{0.0f, 0.0f, 1.0f};      ///< Unit direction from base to apex.
  float apex_radius = 1.0f;         ///< Radius at the apex end, world units; same sign as base.
  float height = 1.0f;              ///< Distance from base to apex along axis, world units (> 0).
  std::uint32_t material = 0;       ///< Index into Scene::materials.
};

/// Whether make_cone can build an axis from these ends: their distance must be a non-zero,
/// finite float (ends 10^38 apart overflow it, ends 10^-30 apart underflow it; either way the
/// axis would come out zero or not a number).
inline bool cone_ends_usable(const Vec3& base, const Vec3& apex) {
  const float h = glm::length(apex - base);
  return h > 0.0f && std::isfinite(h);
}

/// A cone from its two end points and radii (as NFF writes it). Radii may be negative (both),
/// which makes the inside the visible side. The caller checks cone_ends_usable(base, apex).
inline Cone make_cone(const Vec3& base, float base_radius, const Vec3& apex, float apex_radius,
                      std::uint32_t material = 0) {
  Cone c;
  c.base = base;
  c.base_radius = base_radius;
  c.apex_radius = apex_radius;
  const Vec3 d = apex - base;
  c.height = glm::length(d);
  c.axis = d / c.height;
  c.material = material;
  return c;
}

inline Vec3 apex_of(const Cone& c) { return c.base + c.height * c.axis; }

/// Nearest t > ray.tmin where the ray meets the lateral surface, or +inf, in the ray's scalar
/// type (the solve is in double for both).
template <class T>
T cone_distance(const Cone& c, const RayT<T>& ray) {
  using glm::dvec3;
  const dvec3 w(c.axis);
  const dvec3 o = dvec3(ray.org) - dvec3(c.base);
  const dvec3 d(ray.dir);
  const double r0 = std::abs(double(c.base_radius));
  const double h = double(c.height);
  const double k = (std::abs(double(c.apex_radius)) - r0) / h;  // radius growth per unit height
  const double oz = glm::dot(o, w);
  const double dz = glm::dot(d, w);
  const dvec3 op = o - oz * w;   // origin, perpendicular to the axis
  const dvec3 dp = d - dz * w;   // direction, perpendicular to the axis
  const double ro = r0 + k * oz; // radius of the surface at the origin's height
  // |op + t dp|^2 = (ro + k dz t)^2, i.e. a t^2 + 2 b t + cc = 0.
  const double a = glm::dot(dp, dp) - k * k * dz * dz;
  const double b = glm::dot(op, dp) - k * dz * ro;
  const double cc = glm::dot(op, op) - ro * ro;
  const double disc = b * b - a * cc;
  if (!(disc >= 0.0)) return kInfinityOf<T>;
  // Stable roots; a == 0 (ray parallel to a generator line) leaves the single root cc / q.
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  double t0 = q / a;
  double t1 = cc / q;
  if (t0 > t1) std::swap(t0, t1);
  for (const double t : {t0, t1}) {
    const T tt = T(t);
    if (!(tt > ray.tmin) || !(tt < kInfinityOf<T>)) continue;
    const double z = oz + t * dz;
    if (z >= 0.0 && z <= h) return tt;
  }
  return kInfinityOf<T>;
}

inline float intersect(const Cone& c, const Ray& ray) { return cone_distance<float>(c, ray); }
inline double intersect(const Cone& c, const RayD& ray) { return cone_distance<double>(c, ray); }

/// Tight box: each end is a disc of radius r perpendicular to the axis, whose extent along
/// world axis i is r * sqrt(1 - axis[i]^2).
inline accel::Aabb bounds(const Cone& c) {
  const Vec3 spread = glm::sqrt(glm::max(Vec3(1.0f) - c.axis * c.axis, Vec3(0.0f)));
  const Vec3 e0 = std::abs(c.base_radius) * spread;
  const Vec3 e1 = std::abs(c.apex_radius) * spread;
  const Vec3 apex = apex_of(c);
  accel::Aabb box{c.base - e0, c.base + e0};
  box.grow(accel::Aabb{apex - e1, apex + e1});
  // Widen by a few ulps: the sqrt and products above round, and a box must never clip its cone.
  const Vec3 pad = accel::gamma_bound(4) * (glm::abs(box.lo) + glm::abs(box.hi));
  return {box.lo - pad, box.hi + pad};
}

/// Unit normal of the visible side at a point on the surface: outward, or inward when the
/// radii are negative.
inline Vec3 normal_at(const Cone& c, const Vec3& p) {
  const Vec3 o = p - c.base;
  const float z = glm::dot(o, c.axis);
  const Vec3 radial = o - z * c.axis;
  const float r0 = std::abs(c.base_radius);
  const float k = (std::abs(c.apex_radius) - r0) / c.height;
  // Gradient of |radial|^2 - r(z)^2, halved: radial - r(z) k axis.
  Vec3 n = radial - (r0 + k * z) * k * c.axis;
  const float len = glm::length(n);
  n = len > 0.0f ? n / len : -c.axis;  // only at a sharp apex
  return c.base_radius < 0.0f ? -n : n;
}

}  // namespace tracer
