#pragma once
// Ray–sphere intersection that stays exact far from the ray origin.

#include "scalar.h"

#include "accel/geometry.h"

#include <cmath>
#include <cstdint>
#include <utility>

namespace tracer {

using accel::Ray;
using accel::Vec3;

struct Sphere {
  Vec3 center{0.0f};        ///< Centre, world units.
  float radius = 1.0f;      ///< Radius, world units (> 0).
  std::uint32_t material = 0;  ///< Index into Scene::materials.
};

/// Nearest root t > tmin of |org + t dir - center| = radius, or +inf when there is none, in the
/// scalar type of the ray (float or double).
///
/// The discriminant is computed as a (r^2 - |f - (f.d / a) d|^2), which keeps its precision when
/// the sphere is many radii away, where b^2 - ac cancels to noise; the roots use the stable form
/// q = -b - sign(b) sqrt(disc), t0 = c / q, t1 = q / a (Ray Tracing Gems, ch. 7).
template <class T>
T sphere_distance(const Vec3T<T>& center, T radius, const RayT<T>& ray) {
  const Vec3T<T> f = ray.org - center;
  const T a = glm::dot(ray.dir, ray.dir);
  const T b = glm::dot(f, ray.dir);  // half of the usual b
  const Vec3T<T> l = f - (b / a) * ray.dir;
  const T r2 = radius * radius;
  const T disc = a * (r2 - glm::dot(l, l));
  if (!(disc >= T(0))) return kInfinityOf<T>;
  const T c = glm::dot(f, f) - r2;
  const T q = -b - std::copysign(std::sqrt(disc), b);
  T t0 = c / q;
  T t1 = q / a;
  if (q == T(0)) t0 = t1 = T(0);  // ray origin at the centre of a zero sphere; degenerate
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > ray.tmin) return t0;
  if (t1 > ray.tmin) return t1;
  return kInfinityOf<T>;
}

inline float intersect_sphere(const Vec3& center, float radius, const Ray& ray) {
  return sphere_distance<float>(center, radius, ray);
}

inline float intersect(const Sphere& s, const Ray& ray) {
  return sphere_distance<float>(s.center, s.radius, ray);
}
inline double intersect(const Sphere& s, const RayD& ray) {
  return sphere_distance<double>(glm::dvec3(s.center), double(s.radius), ray);
}

inline accel::Aabb bounds(const Sphere& s) {
  const Vec3 r(std::abs(s.radius));
  return {s.center - r, s.center + r};
}

/// Outward unit normal at a point on the sphere.
inline Vec3 normal_at(const Sphere& s, const Vec3& p) { return glm::normalize(p - s.center); }

}  // namespace tracer
