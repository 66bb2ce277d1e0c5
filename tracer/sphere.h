#pragma once
// Ray–sphere intersection that stays exact far from the ray origin.

#include "scalar.h"

#include "accel/geometry.h"
#include "accel/sphere_root.h"

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
/// scalar type of the ray (float or double): accel's one routine (accel/sphere_root.h), which the
/// structures' SIMD sphere leaves match bit for bit.
template <class T>
T sphere_distance(const Vec3T<T>& center, T radius, const RayT<T>& ray) {
  return accel::sphere_root<T>(center, radius, ray);
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
