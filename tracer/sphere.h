#pragma once
// Ray–sphere intersection that stays exact far from the ray origin.

#include "accel/geometry.h"

#include <cmath>
#include <cstdint>

namespace tracer {

using accel::Ray;
using accel::Vec3;

struct Sphere {
  Vec3 center{0.0f};        ///< Centre, world units.
  float radius = 1.0f;      ///< Radius, world units (> 0).
  std::uint32_t material = 0;  ///< Index into Scene::materials.
};

/// Nearest root t > tmin of |org + t dir - center| = radius, or +inf when there is none.
///
/// The discriminant is computed as a (r^2 - |f - (f.d / a) d|^2), which keeps its precision when
/// the sphere is many radii away, where b^2 - ac cancels to noise; the roots use the stable form
/// q = -b - sign(b) sqrt(disc), t0 = c / q, t1 = q / a (Ray Tracing Gems, ch. 7).
inline float intersect_sphere(const Vec3& center, float radius, const Ray& ray) {
  const Vec3 f = ray.org - center;
  const float a = glm::dot(ray.dir, ray.dir);
  const float b = glm::dot(f, ray.dir);  // half of the usual b
  const Vec3 l = f - (b / a) * ray.dir;
  const float r2 = radius * radius;
  const float disc = a * (r2 - glm::dot(l, l));
  if (!(disc >= 0.0f)) return accel::kInfinity;
  const float c = glm::dot(f, f) - r2;
  const float q = -b - std::copysign(std::sqrt(disc), b);
  float t0 = c / q;
  float t1 = q / a;
  if (q == 0.0f) t0 = t1 = 0.0f;  // ray origin at the centre of a zero sphere; degenerate
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > ray.tmin) return t0;
  if (t1 > ray.tmin) return t1;
  return accel::kInfinity;
}

inline float intersect(const Sphere& s, const Ray& ray) {
  return intersect_sphere(s.center, s.radius, ray);
}

inline accel::Aabb bounds(const Sphere& s) {
  const Vec3 r(std::abs(s.radius));
  return {s.center - r, s.center + r};
}

/// Outward unit normal at a point on the sphere.
inline Vec3 normal_at(const Sphere& s, const Vec3& p) { return glm::normalize(p - s.center); }

}  // namespace tracer
