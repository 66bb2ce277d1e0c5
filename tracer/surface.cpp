#include "surface.h"

#include "rounding.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace tracer {

namespace {

template <class T>
constexpr T gamma(int n) {
  return rounding_gamma<T>(n);
}

/// A bound, as a float, on |distance|: the signed distance of a float hit point from its surface,
/// computed in double from the point's exact value (to ~1e-16 of `scale`). It is enlarged for
/// that rounding, and for the direction of the normal it is applied along, which is a few float
/// ulps off the exact one. Measuring the rounding of the point this way, instead of bounding it
/// by ulps of every coordinate, keeps the offset near the true error (half an ulp) far out.
float measured_distance_bound(double distance, double scale) {
  return float((std::abs(distance) + 0x1p-48 * scale) * (1.0 + 0x1p-18));
}

template <class T>
SurfacePointT<T> on_sphere(const Sphere& s, const RayT<T>& ray, T t) {
  SurfacePointT<T> sp;
  const Vec3T<T> centre(s.center);
  // The normal comes from the hit relative to the centre, (org - centre) + t dir, which keeps
  // its precision when both are far from the world origin (org + t dir would first be rounded
  // to an ulp of the coordinates: 0.001 at 1e4, a 2-millirad tilt on a sphere of radius 0.5).
  // Re-projecting onto the sphere removes the error of the ray point, which grows with t: the
  // point is centre + |r| n for the computed unit n, whose rounding is a few ulps of |r n|, plus
  // one rounding of the sum (pbrt-v4 ch. 6.8.5, written in world space: centre + offset).
  sp.n_geo = glm::normalize((ray.org - centre) + t * ray.dir);
  const Vec3T<T> rn = T(std::abs(s.radius)) * sp.n_geo;
  sp.p = centre + rn;
  // gamma(8) |r n|: the rounding of r n, and the sphere test's own error in telling inside from
  // outside near the surface (|f|^2 - r^2 to ~6 ulps of r^2), which sets the least offset at
  // which a leaving ray surely misses. The rounding of centre + r n, an ulp of |p|, is measured.
  if constexpr (std::is_same_v<T, float>)
  {
    const double from_centre = glm::length(glm::dvec3(sp.p) - glm::dvec3(centre));
    const double radius = std::abs(double(s.radius));
    sp.p_error = measured_distance_bound(from_centre - radius, from_centre + radius) *
                     glm::abs(sp.n_geo) +
                 gamma<T>(8) * glm::abs(rn);
  }
  else
    sp.p_error = gamma<T>(1) * glm::abs(sp.p) + gamma<T>(8) * glm::abs(rn);
  sp.n_shade = sp.n_geo;
  sp.material = s.material;
  return sp;
}

template <class T>
SurfacePointT<T> on_triangle(const Geometry& g, const Triangle& tri, const RayT<T>& ray, T t,
                             TriangleTest test) {
  SurfacePointT<T> sp;
  const Vec3T<T> p0(tri.p0), p1(tri.p1), p2(tri.p2);
  T u = T(0), v = T(0);
  if (triangle_distance<T>(test, p0, p1, p2, ray, &u, &v) == kInfinityOf<T>) {
    // A hit another routine found (Embree's own triangles, a peer within a tolerance) that ours
    // misses by a rounding at an edge: the barycentrics of the point at t, clamped into the
    // triangle, so that the point lies on it rather than at p0.
    const Vec3T<T> e1 = p1 - p0, e2 = p2 - p0, d = ray.org + t * ray.dir - p0;
    const T a = glm::dot(e1, e1), b = glm::dot(e1, e2), c = glm::dot(e2, e2);
    const T det = a * c - b * b;
    if (det > T(0)) {
      const T p = glm::dot(d, e1), q = glm::dot(d, e2);
      u = std::clamp((c * p - b * q) / det, T(0), T(1));
      v = std::clamp((a * q - b * p) / det, T(0), T(1) - u);
    }
  }
  const T w = T(1) - u - v;
  // p0 + (u e1 + v e2): within an ulp of |p| plus a few of |u e1| + |v e2| of the plane, where
  // the barycentric w p0 + u p1 + v p2 is a few ulps of every |p_i| off.
  const Vec3T<T> e1 = p1 - p0, e2 = p2 - p0;
  sp.p = p0 + (u * e1 + v * e2);
  // Moller-Trumbore needs a further offset before it surely tells the sides apart: its t carries
  // a few ulps of |p - p0| |e1| |e2| / |e1 x e2|, the edge over the sine of the corner angle. The
  // watertight test needs none: it keeps a hit only where its t is surely positive.
  const glm::dvec3 d1 = glm::dvec3(tri.p1) - glm::dvec3(tri.p0);
  const glm::dvec3 d2 = glm::dvec3(tri.p2) - glm::dvec3(tri.p0);
  const glm::dvec3 normal = glm::cross(d1, d2);
  const double area2 = glm::length(normal);
  const double l1 = glm::length(d1), l2 = glm::length(d2);
  const double robust = area2 > 0.0 && test == TriangleTest::Moller
                            ? double(gamma<T>(9)) * std::max(l1, l2) * l1 * l2 / area2
                            : 0.0;
  T along;
  if constexpr (std::is_same_v<T, float>) {
    const glm::dvec3 dp = glm::dvec3(sp.p) - glm::dvec3(tri.p0);
    const double dist = area2 > 0.0 ? glm::dot(dp, normal) / area2 : 0.0;
    along = measured_distance_bound(dist, glm::length(dp) + l1 + l2) + float(robust);
    sp.p_error = along * glm::abs(glm::normalize(glm::cross(e1, e2)));
  } else {
    sp.p_error = gamma<T>(1) * glm::abs(sp.p) + gamma<T>(4) * (glm::abs(u * e1) + glm::abs(v * e2)) +
                 T(robust) * glm::abs(glm::normalize(glm::cross(e1, e2)));
  }
  sp.n_geo = glm::normalize(glm::cross(p1 - p0, p2 - p0));  // as geometric_normal(tri)
  sp.n_shade = sp.n_geo;
  if (tri.normals >= 0) {
    const Vec3* n = &g.vertex_normals[std::size_t(tri.normals)];
    const Vec3T<T> ns = w * Vec3T<T>(n[0]) + u * Vec3T<T>(n[1]) + v * Vec3T<T>(n[2]);
    const T len = glm::length(ns);
    if (len > T(0)) sp.n_shade = ns / len;
  }
  sp.material = tri.material;
  return sp;
}

template <class T>
SurfacePointT<T> on_box(const Box& box, const RayT<T>& ray, T t) {
  SurfacePointT<T> sp;
  sp.p = ray.org + t * ray.dir;
  // The face is the slab whose entry (or exit) distance the intersection returned, found by
  // repeating its arithmetic exactly: deciding by the nearest face instead misjudges hits near
  // an edge of a thin box, where the rounding of p outweighs the distance to the other face.
  int axis = -1;
  T sign = T(1);
  for (int a = 0; a < 3 && axis < 0; ++a) {
    const T inv = T(1) / ray.dir[a];
    const T t_lo = (T(box.lo[a]) - ray.org[a]) * inv;
    const T t_hi = (T(box.hi[a]) - ray.org[a]) * inv;
    if (t_lo == t)
      axis = a, sign = T(-1);
    else if (t_hi == t)
      axis = a, sign = T(1);
  }
  if (axis < 0) {
    sp.n_geo = Vec3T<T>(normal_at(box, Vec3(sp.p)));
  } else {
    sp.n_geo = Vec3T<T>(T(0));
    sp.n_geo[axis] = sign;
  }
  // Along the face's axis the point is snapped onto the face, exactly; across the face it is
  // org + t dir, whose t is the slab distance (3 roundings) and whose sum rounds twice.
  const Vec3T<T> td = glm::abs(t * ray.dir);
  sp.p_error = gamma<T>(5) * td + gamma<T>(2) * glm::abs(sp.p);
  for (int a = 0; a < 3; ++a)
    if (sp.n_geo[a] != T(0)) {
      sp.p[a] = sp.n_geo[a] > T(0) ? T(box.hi[a]) : T(box.lo[a]);
      sp.p_error[a] = T(0);
    }
  sp.n_shade = sp.n_geo;
  sp.material = box.material;
  return sp;
}

/// A priori bound on the distance, along a unit normal n, between p = q - s n (s the computed
/// signed distance of q from the plane, measured from `ref`) and the plane: the dot product's
/// rounding over |n| |q - ref|, the roundings of p itself, and |s| times the normal's deviation
/// from unit length (at most 4 epsilon of its square, tracer/scene_json.cpp).
template <class T>
T plane_projection_error(const Vec3T<T>& n, const Vec3T<T>& q_minus_ref, const Vec3T<T>& p, T s) {
  const Vec3T<T> an = glm::abs(n);
  return gamma<T>(6) * glm::dot(an, glm::abs(q_minus_ref)) + gamma<T>(3) * glm::dot(an, glm::abs(p)) +
         rounding_gamma<float>(12) * std::abs(s);
}

/// True when n has one non-zero component, of magnitude 1: a plane test then computes
/// offset - o_i exactly for an origin next to the plane (Sterbenz), so it needs no margin.
inline bool axis_aligned(const Vec3& n) {
  const Vec3 a = glm::abs(n);
  return (a.x == 1.0f && a.y == 0.0f && a.z == 0.0f) || (a.x == 0.0f && a.y == 1.0f && a.z == 0.0f) ||
         (a.x == 0.0f && a.y == 0.0f && a.z == 1.0f);
}

template <class T>
SurfacePointT<T> on_plane(const Plane& pl, const RayT<T>& ray, T t) {
  SurfacePointT<T> sp;
  const Vec3T<T> n(pl.normal);
  const Vec3T<T> q = ray.org + t * ray.dir;
  const T s = glm::dot(n, q) - T(pl.offset);
  sp.p = q - s * n;
  T along;
  if constexpr (std::is_same_v<T, float>) {
    // The point's own distance, measured; plus, unless the normal is axis-aligned, the plane
    // test's error in offset - n.o (a few ulps of |n||o| and |offset|, as it measures from the
    // world origin), so that a leaving ray surely misses.
    const glm::dvec3 nd(pl.normal);
    const double dist = (glm::dot(nd, glm::dvec3(sp.p)) - double(pl.offset)) / glm::length(nd);
    const float test = axis_aligned(pl.normal)
                           ? 0.0f
                           : gamma<T>(4) * (glm::dot(glm::abs(n), glm::abs(sp.p)) + std::abs(pl.offset));
    along = measured_distance_bound(dist, glm::dot(glm::abs(nd), glm::abs(glm::dvec3(sp.p))) +
                                              std::abs(double(pl.offset))) +
            test;
  } else {
    // Measured from the world origin, as the plane test measures: |offset| enters like |q|.
    along = plane_projection_error<T>(n, q, sp.p, s) + gamma<T>(4) * std::abs(T(pl.offset));
  }
  sp.p_error = along * glm::abs(n);
  sp.n_geo = n;
  sp.n_shade = n;
  sp.material = pl.material;
  return sp;
}

template <class T>
SurfacePointT<T> on_cone(const Cone& c, const RayT<T>& ray, T t) {
  SurfacePointT<T> sp;
  // Re-projected in double onto the surface exactly as intersect(Cone) defines it: the height
  // o.w is kept and the radial part scaled to the radius there. The double arithmetic is exact
  // to ~1e-16 relative, so a float point is within its own rounding of the surface; a double
  // point within a few of its ulps of |radial|.
  using glm::dvec3;
  const dvec3 q(ray.org + t * ray.dir);
  const dvec3 w(c.axis);
  const dvec3 o = q - dvec3(c.base);
  const double r0 = std::abs(double(c.base_radius));
  const double k = (std::abs(double(c.apex_radius)) - r0) / double(c.height);
  const double z = glm::dot(o, w);
  const dvec3 radial = o - z * w;
  const double rho = glm::length(radial);
  const dvec3 p = rho > 0.0 ? q + ((r0 + k * z) / rho - 1.0) * radial : q;
  sp.p = Vec3T<T>(p);
  if constexpr (std::is_same_v<T, float>) {
    // The rounded point's own distance from the surface, measured in double (the cone test
    // solves in double, so it needs no margin of its own).
    const dvec3 of = dvec3(sp.p) - dvec3(c.base);
    const double zf = glm::dot(of, w);
    const double dist = (glm::length(of - zf * w) - (r0 + k * zf)) / std::sqrt(1.0 + k * k);
    sp.p_error = Vec3T<T>(measured_distance_bound(dist, glm::length(of) + r0 + std::abs(k * zf)));
  } else {
    sp.p_error = gamma<T>(2) * glm::abs(sp.p) + gamma<T>(8) * Vec3T<T>(glm::abs(radial));
  }
  // The normal from the same unrounded local coordinates (the gradient radial / rho - k w,
  // as normal_at computes it from a float point), inward when the radii are negative.
  if (rho > 0.0) {
    const Vec3T<T> n(glm::normalize(radial / rho - k * w));
    sp.n_geo = c.base_radius < 0.0f ? -n : n;
  } else {
    sp.n_geo = Vec3T<T>(normal_at(c, Vec3(sp.p)));
  }
  if constexpr (std::is_same_v<T, float>) sp.p_error *= glm::abs(sp.n_geo);  // along the normal
  sp.n_shade = sp.n_geo;
  sp.material = c.material;
  return sp;
}

template <class T>
SurfacePointT<T> on_polygon(const Geometry& g, const Polygon& poly, const RayT<T>& ray, T t) {
  SurfacePointT<T> sp;
  const Vec3T<T> n(poly.normal);
  const Vec3T<T> q = ray.org + t * ray.dir;
  // Measured from the first vertex, as the polygon test measures.
  const Vec3 v0f = g.polygon_vertices[poly.first_vertex];
  const Vec3T<T> v0(v0f);
  const Vec3T<T> d = q - v0;
  const T s = glm::dot(n, d);
  sp.p = q - s * n;
  if constexpr (std::is_same_v<T, float>) {
    // The point's own distance, measured, plus the polygon test's error in n.(v0 - o), a few
    // ulps of |n||p - v0| (the polygon's size, not its distance from the world origin).
    const glm::dvec3 nd(poly.normal);
    const glm::dvec3 dp = glm::dvec3(sp.p) - glm::dvec3(v0f);
    const float along = measured_distance_bound(glm::dot(nd, dp) / glm::length(nd), glm::length(dp)) +
                        gamma<T>(4) * glm::dot(glm::abs(n), glm::abs(sp.p - v0));
    sp.p_error = along * glm::abs(n);
  } else {
    sp.p_error = plane_projection_error<T>(n, d, sp.p, s) * glm::abs(n);
  }
  sp.n_geo = n;
  sp.n_shade = n;
  sp.material = poly.material;
  return sp;
}

template <class T>
SurfacePointT<T> surface_point_of(const Geometry& g, const RayT<T>& ray, const HitT<T>& hit,
                                  TriangleTest triangles_by) {
  if (hit.is_plane()) return on_plane<T>(g.planes[hit.prim & ~HitT<T>::kPlaneBit], ray, hit.t);
  const std::uint32_t id = hit.prim;
  switch (g.kind_of(id)) {
    case PrimitiveKind::Sphere:
      return on_sphere<T>(g.spheres[id - g.first_id[0]], ray, hit.t);
    case PrimitiveKind::Triangle:
      return on_triangle<T>(g, g.triangles[id - g.first_id[1]], ray, hit.t, triangles_by);
    case PrimitiveKind::Box:
      return on_box<T>(g.boxes[id - g.first_id[2]], ray, hit.t);
    case PrimitiveKind::Cone:
      return on_cone<T>(g.cones[id - g.first_id[3]], ray, hit.t);
    case PrimitiveKind::Polygon:
      return on_polygon<T>(g, g.polygons[id - g.first_id[4]], ray, hit.t);
    case PrimitiveKind::Count:
      break;
  }
  return {};
}

}  // namespace

SurfacePoint surface_point(const Geometry& g, const Ray& ray, const Hit& hit, TriangleTest triangles_by) {
  return surface_point_of<float>(g, ray, hit, triangles_by);
}

SurfacePointD surface_point(const Geometry& g, const RayD& ray, const HitD& hit, TriangleTest triangles_by) {
  return surface_point_of<double>(g, ray, hit, triangles_by);
}

}  // namespace tracer
