#pragma once
// Axis-aligned box primitive: a solid, closed surface.

#include "accel/ray_setup.h"

#include <cmath>
#include <cstdint>

namespace tracer {

using accel::Ray;
using accel::Vec3;

struct Box {
  Vec3 lo{-0.5f};  ///< Minimum corner, world units.
  Vec3 hi{0.5f};   ///< Maximum corner, world units (each component > lo's).
  std::uint32_t material = 0;  ///< Index into Scene::materials.
};

/// Nearest surface crossing t > tmin: the entry distance, or the exit distance from inside.
inline float intersect(const Box& box, const Ray& ray) {
  float t_enter = -accel::kInfinity, t_exit = accel::kInfinity;
  for (int a = 0; a < 3; ++a) {
    const float inv = 1.0f / ray.dir[a];
    float t_near = (box.lo[a] - ray.org[a]) * inv;
    float t_far = (box.hi[a] - ray.org[a]) * inv;
    if (t_near > t_far) std::swap(t_near, t_far);
    t_enter = t_near > t_enter ? t_near : t_enter;
    t_exit = t_far < t_exit ? t_far : t_exit;
  }
  if (!(t_enter <= t_exit)) return accel::kInfinity;
  if (t_enter > ray.tmin) return t_enter;
  if (t_exit > ray.tmin) return t_exit;
  return accel::kInfinity;
}

inline accel::Aabb bounds(const Box& box) { return {box.lo, box.hi}; }

/// Outward unit normal of the face nearest to p.
inline Vec3 normal_at(const Box& box, const Vec3& p) {
  const Vec3 c = 0.5f * (box.lo + box.hi);
  const Vec3 half = 0.5f * (box.hi - box.lo);
  const Vec3 d = (p - c) / half;
  const Vec3 ad = glm::abs(d);
  int axis = (ad.x >= ad.y && ad.x >= ad.z) ? 0 : (ad.y >= ad.z ? 1 : 2);
  Vec3 n(0.0f);
  n[axis] = d[axis] >= 0.0f ? 1.0f : -1.0f;
  return n;
}

}  // namespace tracer
