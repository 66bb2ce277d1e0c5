#pragma once
// Infinite plane: unbounded, so it is tested outside the acceleration structures.

#include "scalar.h"

#include "accel/geometry.h"

#include <cstdint>

namespace tracer {

using accel::Ray;
using accel::Vec3;

struct Plane {
  Vec3 normal{0.0f, 1.0f, 0.0f};  ///< Unit normal; the front side faces along it.
  float offset = 0.0f;            ///< Points p on the plane satisfy dot(normal, p) = offset.
  std::uint32_t material = 0;     ///< Index into Scene::materials.
};

/// Distance t > tmin to the plane in the ray's scalar type, or +inf.
template <class T>
T plane_distance(const Plane& pl, const RayT<T>& ray) {
  const Vec3T<T> n(pl.normal);
  const T denom = glm::dot(n, ray.dir);
  if (denom == T(0)) return kInfinityOf<T>;
  const T t = (T(pl.offset) - glm::dot(n, ray.org)) / denom;
  return t > ray.tmin ? t : kInfinityOf<T>;
}

inline float intersect(const Plane& pl, const Ray& ray) { return plane_distance<float>(pl, ray); }
inline double intersect(const Plane& pl, const RayD& ray) { return plane_distance<double>(pl, ray); }

}  // namespace tracer
