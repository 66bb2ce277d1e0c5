#pragma once
// Planar polygon with any number of vertices, convex or concave (NFF's `p` with n > 3).
//
// A hit is the plane hit followed by an even-odd (crossing-number) test in the 2-D projection
// that drops the normal's dominant axis. One primitive per NFF polygon, rather than a triangle
// fan: a fan is wrong for concave polygons (the 144-gon gear faces), and even for convex ones
// a fan of non-watertight triangle tests can leak rays along its internal diagonals.
//
// Edge rule (half-open, like a rasteriser's fill rule): in the projected (u, v) frame a point
// on an edge is inside when the polygon lies to its right along +u, i.e. the crossing test
// counts edges with v in [v_lo, v_hi) whose crossing lies strictly right of the point. So for an
// axis-aligned square the left and bottom edges are inside and the right and top edges outside,
// and a point on an edge shared by two coplanar polygons is inside exactly one of them. Every
// edge is evaluated from its lower endpoint, so both polygons compute the same crossing.

#include "scalar.h"

#include "accel/geometry.h"

#include <cmath>
#include <cstdint>
#include <span>
#include <utility>

namespace tracer {

using accel::Ray;
using accel::Vec3;

struct Polygon {
  Vec3 normal{0.0f, 0.0f, 1.0f};  ///< Unit normal by the right-hand rule over the vertex order.
  std::uint32_t first_vertex = 0;  ///< Index of the first vertex in Geometry::polygon_vertices.
  std::uint32_t vertex_count = 0;  ///< Number of vertices (>= 3).
  std::uint32_t material = 0;      ///< Index into Scene::materials.
  std::uint8_t drop_axis = 2;      ///< Axis (0, 1, 2) dropped for the 2-D test: the normal's largest.
};

/// Polygon over `vertices` (which the caller stores at first_vertex); the normal is Newell's,
/// exact for concave polygons and not fooled by a collinear first corner. A degenerate polygon
/// gets a zero normal and is never hit.
inline Polygon make_polygon(std::span<const Vec3> vertices, std::uint32_t first_vertex,
                            std::uint32_t material = 0) {
  Vec3 n(0.0f);
  const std::size_t count = vertices.size();
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3& a = vertices[i];
    const Vec3& b = vertices[(i + 1) % count];
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  const float len = glm::length(n);
  Polygon p;
  p.normal = len > 0.0f ? n / len : Vec3(0.0f);
  p.first_vertex = first_vertex;
  p.vertex_count = std::uint32_t(count);
  p.material = material;
  const Vec3 an = glm::abs(p.normal);
  p.drop_axis = std::uint8_t((an.x >= an.y && an.x >= an.z) ? 0 : (an.y >= an.z ? 1 : 2));
  return p;
}

/// Even-odd test of the projected point (pu, pv) against the polygon's projected edges, with
/// the half-open edge rule described at the top of this file, in the scalar type T.
template <class T>
bool polygon_contains(const Polygon& poly, const Vec3* vertices, T pu, T pv) {
  const int ui = (poly.drop_axis + 1) % 3;
  const int vi = (poly.drop_axis + 2) % 3;
  bool inside = false;
  const Vec3* vs = vertices + poly.first_vertex;
  const std::uint32_t n = poly.vertex_count;
  for (std::uint32_t i = 0, j = n - 1; i < n; j = i++) {
    Vec3T<T> lo(vs[j]), hi(vs[i]);
    if (lo[vi] > hi[vi]) std::swap(lo, hi);
    if (!(pv >= lo[vi] && pv < hi[vi])) continue;  // half-open in v; skips horizontal edges
    // Is the crossing at height pv strictly right of pu? Cross-multiplied by (hi.v - lo.v) > 0.
    const T lhs = (pu - lo[ui]) * (hi[vi] - lo[vi]);
    const T rhs = (pv - lo[vi]) * (hi[ui] - lo[ui]);
    if (lhs < rhs) inside = !inside;
  }
  return inside;
}

/// Nearest t > ray.tmin where the ray meets the polygon (either side), or +inf, in the ray's
/// scalar type.
template <class T>
T polygon_distance(const Polygon& poly, const Vec3* vertices, const RayT<T>& ray) {
  const Vec3T<T> n(poly.normal);
  const T denom = glm::dot(n, ray.dir);
  if (denom == T(0) || !std::isfinite(denom)) return kInfinityOf<T>;
  // Measured from the first vertex rather than the world origin, for precision far away.
  const T t = glm::dot(n, Vec3T<T>(vertices[poly.first_vertex]) - ray.org) / denom;
  if (!(t > ray.tmin) || !(t < kInfinityOf<T>)) return kInfinityOf<T>;
  const Vec3T<T> p = ray.org + t * ray.dir;
  const int ui = (poly.drop_axis + 1) % 3;
  const int vi = (poly.drop_axis + 2) % 3;
  return polygon_contains<T>(poly, vertices, p[ui], p[vi]) ? t : kInfinityOf<T>;
}

inline float intersect_polygon(const Polygon& poly, const Vec3* vertices, const Ray& ray) {
  return polygon_distance<float>(poly, vertices, ray);
}
inline double intersect_polygon(const Polygon& poly, const Vec3* vertices, const RayD& ray) {
  return polygon_distance<double>(poly, vertices, ray);
}

inline accel::Aabb bounds(const Polygon& poly, const Vec3* vertices) {
  accel::Aabb box;
  for (std::uint32_t i = 0; i < poly.vertex_count; ++i) box.grow(vertices[poly.first_vertex + i]);
  return box;
}

}  // namespace tracer
