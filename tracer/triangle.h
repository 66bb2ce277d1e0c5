#pragma once
// Ray–triangle intersection (Möller–Trumbore), two-sided.

#include "scalar.h"

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

/// Distance t > tmin to the triangle in the ray's scalar type, or +inf. Barycentrics (u, v) of
/// p1 and p2 when hit.
template <class T>
T triangle_distance(const Vec3T<T>& p0, const Vec3T<T>& p1, const Vec3T<T>& p2,
                    const RayT<T>& ray, T* u_out = nullptr, T* v_out = nullptr) {
  const Vec3T<T> e1 = p1 - p0;
  const Vec3T<T> e2 = p2 - p0;
  const Vec3T<T> pv = glm::cross(ray.dir, e2);
  const T det = glm::dot(e1, pv);
  if (det == T(0) || !std::isfinite(det)) return kInfinityOf<T>;
  const T inv_det = T(1) / det;
  const Vec3T<T> tv = ray.org - p0;
  const T u = glm::dot(tv, pv) * inv_det;
  if (u < T(0) || u > T(1)) return kInfinityOf<T>;
  const Vec3T<T> qv = glm::cross(tv, e1);
  const T v = glm::dot(ray.dir, qv) * inv_det;
  if (v < T(0) || u + v > T(1)) return kInfinityOf<T>;
  const T t = glm::dot(e2, qv) * inv_det;
  if (!(t > ray.tmin)) return kInfinityOf<T>;
  if (u_out) *u_out = u;
  if (v_out) *v_out = v;
  return t;
}

inline float intersect_triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Ray& ray,
                                float* u_out = nullptr, float* v_out = nullptr) {
  return triangle_distance<float>(p0, p1, p2, ray, u_out, v_out);
}

inline float intersect(const Triangle& tri, const Ray& ray) {
  return triangle_distance<float>(tri.p0, tri.p1, tri.p2, ray);
}
inline double intersect(const Triangle& tri, const RayD& ray) {
  return triangle_distance<double>(glm::dvec3(tri.p0), glm::dvec3(tri.p1), glm::dvec3(tri.p2), ray);
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
