#pragma once
// Infinite plane: unbounded, so it is tested outside the acceleration structures.

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

inline float intersect(const Plane& pl, const Ray& ray) {
  const float denom = glm::dot(pl.normal, ray.dir);
  if (denom == 0.0f) return accel::kInfinity;
  const float t = (pl.offset - glm::dot(pl.normal, ray.org)) / denom;
  return t > ray.tmin ? t : accel::kInfinity;
}

}  // namespace tracer
