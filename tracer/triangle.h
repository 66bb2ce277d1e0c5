#pragma once
// Ray–triangle intersection, two-sided: watertight (Woop, Benthin and Wald 2013, as in pbrt-v4)
// and Möller–Trumbore, chosen by the `triangle` knob (triangle_test.h).

#include "rounding.h"
#include "scalar.h"
#include "triangle_test.h"

#include "accel/geometry.h"

#include <algorithm>
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

/// Möller–Trumbore: distance t > tmin to the triangle in the ray's scalar type, or +inf.
/// Barycentrics (u, v) of p1 and p2 when hit.
template <class T>
T moller_distance(const Vec3T<T>& p0, const Vec3T<T>& p1, const Vec3T<T>& p2, const RayT<T>& ray,
                  T* u_out = nullptr, T* v_out = nullptr) {
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

/// Watertight (Woop, Benthin and Wald 2013; pbrt-v4 ch. 6.5.3): distance t > tmin to the
/// triangle, or +inf; barycentrics (u, v) of p1 and p2 when hit.
///
/// The vertices move into a frame where the ray starts at the origin and runs along +z (a
/// translation, a permutation that makes z the largest direction component, and a shear); the
/// three edge functions are then 2D cross products of the sheared vertices. Two triangles that
/// share an edge compute its edge function from the same two vertices with the same operations,
/// exactly negated, so no ray passes between them; an edge function that rounds to exactly 0 is
/// computed again in double (a product of floats is exact there). The hit is kept only when t is
/// above tmin and above the bound on its own rounding error, so a ray leaving the surface from
/// an origin offset by the hit point's error bound (offset_ray.h) never hits it again.
template <class T>
T watertight_distance(const Vec3T<T>& p0, const Vec3T<T>& p1, const Vec3T<T>& p2,
                      const RayT<T>& ray, T* u_out = nullptr, T* v_out = nullptr) {
  // Translate, then permute so that the largest direction component is z.
  const Vec3T<T> ad = glm::abs(ray.dir);
  const int kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
  const int kx = kz == 2 ? 0 : kz + 1;
  const int ky = kx == 2 ? 0 : kx + 1;
  const T dz = ray.dir[kz];
  if (dz == T(0) || !std::isfinite(dz)) return kInfinityOf<T>;
  const T sx = -ray.dir[kx] / dz, sy = -ray.dir[ky] / dz, sz = T(1) / dz;
  const Vec3T<T> a = p0 - ray.org, b = p1 - ray.org, c = p2 - ray.org;
  // Shear x and y so that the ray runs along +z.
  const T ax = a[kx] + sx * a[kz], ay = a[ky] + sy * a[kz];
  const T bx = b[kx] + sx * b[kz], by = b[ky] + sy * b[kz];
  const T cx = c[kx] + sx * c[kz], cy = c[ky] + sy * c[kz];
  T e0 = bx * cy - by * cx;  // edge p1 p2, weight of p0
  T e1 = cx * ay - cy * ax;  // edge p2 p0, weight of p1
  T e2 = ax * by - ay * bx;  // edge p0 p1, weight of p2
  if constexpr (std::is_same_v<T, float>) {
    if (e0 == 0.0f || e1 == 0.0f || e2 == 0.0f) {
      e0 = float(double(bx) * double(cy) - double(by) * double(cx));
      e1 = float(double(cx) * double(ay) - double(cy) * double(ax));
      e2 = float(double(ax) * double(by) - double(ay) * double(bx));
    }
  }
  if ((e0 < T(0) || e1 < T(0) || e2 < T(0)) && (e0 > T(0) || e1 > T(0) || e2 > T(0)))
    return kInfinityOf<T>;
  const T det = e0 + e1 + e2;
  if (det == T(0) || !std::isfinite(det)) return kInfinityOf<T>;
  const T az = sz * a[kz], bz = sz * b[kz], cz = sz * c[kz];
  const T t_scaled = e0 * az + e1 * bz + e2 * cz;
  const T inv_det = T(1) / det;
  const T t = t_scaled * inv_det;
  if (!(t > ray.tmin)) return kInfinityOf<T>;
  // Keep t only where it is surely positive (pbrt-v4's bound on the error of t). The sheared x
  // and y are world lengths, and so is their error, a few ulps of |x| + |sx z| <= |x| + |z| with
  // z in world units: pbrt-v4 adds the z it has scaled by 1/dz, which is another unit. With a
  // short direction (a shadow ray of a scene scaled by 10^-4: |dir| ~ 3e-5, |z / dz| ~ 0.3 beside
  // |x| ~ 1e-7) that bound outgrew t and dropped every hit, and the shadows with them.
  const T max_z = std::max({std::abs(az), std::abs(bz), std::abs(cz)});
  const T max_z_world = std::max({std::abs(a[kz]), std::abs(b[kz]), std::abs(c[kz])});
  const T max_x = std::max({std::abs(ax), std::abs(bx), std::abs(cx)});
  const T max_y = std::max({std::abs(ay), std::abs(by), std::abs(cy)});
  const T delta_z = rounding_gamma<T>(3) * max_z;
  const T delta_x = rounding_gamma<T>(5) * (max_x + max_z_world);
  const T delta_y = rounding_gamma<T>(5) * (max_y + max_z_world);
  const T delta_e = T(2) * (rounding_gamma<T>(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
  const T max_e = std::max({std::abs(e0), std::abs(e1), std::abs(e2)});
  const T delta_t = T(3) * (rounding_gamma<T>(3) * max_e * max_z + delta_e * max_z + delta_z * max_e) *
                    std::abs(inv_det);
  if (!(t > delta_t)) return kInfinityOf<T>;
  if (u_out) *u_out = e1 * inv_det;
  if (v_out) *v_out = e2 * inv_det;
  return t;
}

/// The distance to the triangle by the chosen routine (see above).
template <class T>
T triangle_distance(TriangleTest test, const Vec3T<T>& p0, const Vec3T<T>& p1, const Vec3T<T>& p2,
                    const RayT<T>& ray, T* u_out = nullptr, T* v_out = nullptr) {
  return test == TriangleTest::Moller ? moller_distance<T>(p0, p1, p2, ray, u_out, v_out)
                                      : watertight_distance<T>(p0, p1, p2, ray, u_out, v_out);
}

inline float intersect(const Triangle& tri, const Ray& ray, TriangleTest test) {
  return triangle_distance<float>(test, tri.p0, tri.p1, tri.p2, ray);
}
inline double intersect(const Triangle& tri, const RayD& ray, TriangleTest test) {
  return triangle_distance<double>(test, glm::dvec3(tri.p0), glm::dvec3(tri.p1), glm::dvec3(tri.p2), ray);
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
