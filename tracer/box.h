#pragma once
// Axis-aligned box primitive: a solid, closed surface.

#include "scalar.h"

#include "accel/ray_setup.h"

#include <cmath>
#include <cstdint>
#include <utility>

namespace tracer {

using accel::Ray;
using accel::Vec3;

struct Box {
  Vec3 lo{-0.5f};  ///< Minimum corner, world units.
  Vec3 hi{0.5f};   ///< Maximum corner, world units (each component > lo's).
  std::uint32_t material = 0;  ///< Index into Scene::materials.
};

/// Nearest surface crossing t > tmin: the entry distance, or the exit distance from inside, in
/// the ray's scalar type.
template <class T>
T box_distance(const Box& box, const RayT<T>& ray) {
  T t_enter = -kInfinityOf<T>, t_exit = kInfinityOf<T>;
  for (int a = 0; a < 3; ++a) {
    const T inv = T(1) / ray.dir[a];
    T t_near = (T(box.lo[a]) - ray.org[a]) * inv;
    T t_far = (T(box.hi[a]) - ray.org[a]) * inv;
    if (t_near > t_far) std::swap(t_near, t_far);
    t_enter = t_near > t_enter ? t_near : t_enter;
    t_exit = t_far < t_exit ? t_far : t_exit;
  }
  if (!(t_enter <= t_exit)) return kInfinityOf<T>;
  if (t_enter > ray.tmin) return t_enter;
  if (t_exit > ray.tmin) return t_exit;
  return kInfinityOf<T>;
}

inline float intersect(const Box& box, const Ray& ray) { return box_distance<float>(box, ray); }
inline double intersect(const Box& box, const RayD& ray) { return box_distance<double>(box, ray); }

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
