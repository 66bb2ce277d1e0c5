#include "surface.h"

#include "rounding.h"

#include <glm/vec3.hpp>

#include <cmath>

namespace tracer {

namespace {

constexpr float gamma(int n) { return rounding_gamma<float>(n); }

SurfacePoint on_sphere(const Sphere& s, const Ray& ray, float t) {
  SurfacePoint sp;
  // The normal comes from the hit relative to the centre, (org - centre) + t dir, which keeps
  // its precision when both are far from the world origin (org + t dir would first be rounded
  // to an ulp of the coordinates: 0.001 at 1e4, a 2-millirad tilt on a sphere of radius 0.5).
  // Re-projecting onto the sphere removes the error of the ray point, which grows with t: the
  // point is centre + |r| n for the computed unit n, whose rounding is a few ulps of |r n|, plus
  // one rounding of the sum (pbrt-v4 ch. 6.8.5, written in world space: centre + offset).
  sp.n_geo = glm::normalize((ray.org - s.center) + t * ray.dir);
  const Vec3 rn = std::abs(s.radius) * sp.n_geo;
  sp.p = s.center + rn;
  sp.p_error = gamma(2) * glm::abs(sp.p) + gamma(8) * glm::abs(rn);
  sp.n_shade = sp.n_geo;
  sp.material = s.material;
  return sp;
}

SurfacePoint on_triangle(const Geometry& g, const Triangle& tri, const Ray& ray) {
  SurfacePoint sp;
  float u = 0.0f, v = 0.0f;
  intersect_triangle(tri.p0, tri.p1, tri.p2, ray, &u, &v);
  const float w = 1.0f - u - v;
  // Barycentric: exact to a few ulps of the weighted vertices (pbrt-v4's gamma(7) bound); the
  // rounding of w = 1 - u - v moves the weights' sum off 1 by up to 2 ulps, times |p0|.
  const Vec3 wp0 = w * tri.p0, up1 = u * tri.p1, vp2 = v * tri.p2;
  sp.p = wp0 + up1 + vp2;
  sp.p_error = gamma(7) * (glm::abs(wp0) + glm::abs(up1) + glm::abs(vp2)) +
               gamma(2) * glm::abs(tri.p0);
  sp.n_geo = geometric_normal(tri);
  sp.n_shade = sp.n_geo;
  if (tri.normals >= 0) {
    const Vec3* n = &g.vertex_normals[std::size_t(tri.normals)];
    const Vec3 ns = w * n[0] + u * n[1] + v * n[2];
    const float len = glm::length(ns);
    if (len > 0.0f) sp.n_shade = ns / len;
  }
  sp.material = tri.material;
  return sp;
}

SurfacePoint on_box(const Box& box, const Ray& ray, float t) {
  SurfacePoint sp;
  sp.p = ray.org + t * ray.dir;
  // The face is the slab whose entry (or exit) distance the intersection returned, found by
  // repeating its arithmetic exactly: deciding by the nearest face instead misjudges hits near
  // an edge of a thin box, where the rounding of p outweighs the distance to the other face.
  int axis = -1;
  float sign = 1.0f;
  for (int a = 0; a < 3 && axis < 0; ++a) {
    const float inv = 1.0f / ray.dir[a];
    const float t_lo = (box.lo[a] - ray.org[a]) * inv;
    const float t_hi = (box.hi[a] - ray.org[a]) * inv;
    if (t_lo == t)
      axis = a, sign = -1.0f;
    else if (t_hi == t)
      axis = a, sign = 1.0f;
  }
  if (axis < 0) {
    sp.n_geo = normal_at(box, sp.p);
  } else {
    sp.n_geo = Vec3(0.0f);
    sp.n_geo[axis] = sign;
  }
  // Along the face's axis the point is snapped onto the face, exactly; across the face it is
  // org + t dir, whose t is the slab distance (3 roundings) and whose sum rounds twice.
  const Vec3 td = glm::abs(t * ray.dir);
  sp.p_error = gamma(5) * td + gamma(2) * glm::abs(sp.p);
  for (int a = 0; a < 3; ++a)
    if (sp.n_geo[a] != 0.0f) {
      sp.p[a] = sp.n_geo[a] > 0.0f ? box.hi[a] : box.lo[a];
      sp.p_error[a] = 0.0f;
    }
  sp.n_shade = sp.n_geo;
  sp.material = box.material;
  return sp;
}

/// Bound on the distance, along a unit normal n, between p = q - s n (s the computed signed
/// distance of q from the plane, measured from `ref`) and the plane: the dot product's rounding
/// over |n| |q - ref|, the roundings of p itself, and |s| times the normal's deviation from unit
/// length (at most 4 epsilon of its square, tracer/scene_json.cpp).
float plane_projection_error(const Vec3& n, const Vec3& q_minus_ref, const Vec3& p, float s) {
  const Vec3 an = glm::abs(n);
  return gamma(6) * glm::dot(an, glm::abs(q_minus_ref)) + gamma(3) * glm::dot(an, glm::abs(p)) +
         gamma(12) * std::abs(s);
}

SurfacePoint on_plane(const Plane& pl, const Ray& ray, float t) {
  SurfacePoint sp;
  const Vec3 q = ray.org + t * ray.dir;
  const float s = glm::dot(pl.normal, q) - pl.offset;
  sp.p = q - s * pl.normal;
  // Measured from the world origin, as the plane test measures: |offset| enters like |q|.
  const float along = plane_projection_error(pl.normal, q, sp.p, s) + gamma(2) * std::abs(pl.offset);
  sp.p_error = along * glm::abs(pl.normal);
  sp.n_geo = pl.normal;
  sp.n_shade = pl.normal;
  sp.material = pl.material;
  return sp;
}

SurfacePoint on_cone(const Cone& c, const Ray& ray, float t) {
  SurfacePoint sp;
  // Re-projected in double onto the surface exactly as intersect(Cone) defines it: the height
  // o.w is kept and the radial part scaled to the radius there. The double arithmetic is exact
  // to ~1e-16 relative, so the float point is within its own rounding of the surface.
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
  sp.p = Vec3(p);
  sp.p_error = gamma(2) * glm::abs(sp.p) + gamma(1) * Vec3(glm::abs(radial));
  // The normal from the same unrounded local coordinates (the gradient radial / rho - k w,
  // as normal_at computes it from a float point), inward when the radii are negative.
  if (rho > 0.0) {
    const Vec3 n(glm::normalize(radial / rho - k * w));
    sp.n_geo = c.base_radius < 0.0f ? -n : n;
  } else {
    sp.n_geo = normal_at(c, sp.p);
  }
  sp.n_shade = sp.n_geo;
  sp.material = c.material;
  return sp;
}

SurfacePoint on_polygon(const Geometry& g, const Polygon& poly, const Ray& ray, float t) {
  SurfacePoint sp;
  const Vec3 q = ray.org + t * ray.dir;
  // Measured from the first vertex, as the polygon test measures.
  const Vec3 v0 = g.polygon_vertices[poly.first_vertex];
  const Vec3 d = q - v0;
  const float s = glm::dot(poly.normal, d);
  sp.p = q - s * poly.normal;
  sp.p_error = plane_projection_error(poly.normal, d, sp.p, s) * glm::abs(poly.normal);
  sp.n_geo = poly.normal;
  sp.n_shade = poly.normal;
  sp.material = poly.material;
  return sp;
}

}  // namespace

SurfacePoint surface_point(const Geometry& g, const Ray& ray, const Hit& hit) {
  if (hit.is_plane()) return on_plane(g.planes[hit.prim & ~Hit::kPlaneBit], ray, hit.t);
  const std::uint32_t id = hit.prim;
  switch (g.kind_of(id)) {
    case PrimitiveKind::Sphere:
      return on_sphere(g.spheres[id - g.first_id[0]], ray, hit.t);
    case PrimitiveKind::Triangle: {
      const Triangle& tri = g.triangles[id - g.first_id[1]];
      return on_triangle(g, tri, ray);
    }
    case PrimitiveKind::Box:
      return on_box(g.boxes[id - g.first_id[2]], ray, hit.t);
    case PrimitiveKind::Cone:
      return on_cone(g.cones[id - g.first_id[3]], ray, hit.t);
    case PrimitiveKind::Polygon:
      return on_polygon(g, g.polygons[id - g.first_id[4]], ray, hit.t);
    case PrimitiveKind::Count:
      break;
  }
  return {};
}

}  // namespace tracer
