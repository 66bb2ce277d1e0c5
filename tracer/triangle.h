#pragma once
// Ray–triangle intersection (Möller–Trumbore), two-sided.

#include "accel/geometry.h"

#include <cmath>
#include <cstdint>

namespace tracer {

using accel::Ray;
using accel::Vec3;

struct Triangle {
  Vec3 p0{0.0f}, p1{1.0f, 0.0f, 0.0f}, p2{0.0f, 1.0f, 0.0f};  ///< Vertices, counter-clockwise.
  std::uint32_t material = 0;  ///< Index into Scene::materials.
  std::int32_t normals = -1;   ///< Index of three vertex normals in Geometry::vertex_normals, or -1.
};

/// Distance t > tmin to the triangle, or +inf. Barycentrics (u, v) of p1 and p2 when hit.
inline float intersect_triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Ray& ray,
                                float* u_out = nullptr, float* v_out = nullptr) {
  const Vec3 e1 = p1 - p0;
  const Vec3 e2 = p2 - p0;
  const Vec3 pv = glm::cross(ray.dir, e2);
  const float det = glm::dot(e1, pv);
  if (det == 0.0f || !std::isfinite(det)) return accel::kInfinity;
  const float inv_det = 1.0f / det;
  const Vec3 tv = ray.org - p0;
  const float u = glm::dot(tv, pv) * inv_det;
  if (u < 0.0f || u > 1.0f) return accel::kInfinity;
  const Vec3 qv = glm::cross(tv, e1);
  const float v = glm::dot(ray.dir, qv) * inv_det;
  if (v < 0.0f || u + v > 1.0f) return accel::kInfinity;
  const float t = glm::dot(e2, qv) * inv_det;
  if (!(t > ray.tmin)) return accel::kInfinity;
  if (u_out) *u_out = u;
  if (v_out) *v_out = v;
  return t;
}

inline float intersect(const Triangle& tri, const Ray& ray) {
  return intersect_triangle(tri.p0, tri.p1, tri.p2, ray);
}

inline accel::Aabb bounds(const Triangle& tri) {
  accel::Aabb b = accel::Aabb::of_point(tri.p0);
  b.grow(tri.p1);
  b.grow(tri.p2);
  return b;
}

/// Geometric unit normal, by the right-hand rule over p0, p1, p2.
inline Vec3 geometric_normal(const Triangle& tri) {
  return glm::normalize(glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0));
}

}  // namespace tracer
