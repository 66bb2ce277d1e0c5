#include "surface.h"

#include <cmath>

namespace tracer {

namespace {

SurfacePoint on_sphere(const Sphere& s, const Ray& ray, float t) {
  SurfacePoint sp;
  // Re-projecting onto the sphere removes the error of org + t dir, which grows with t.
  sp.n_geo = glm::normalize(ray.org + t * ray.dir - s.center);
  sp.p = s.center + std::abs(s.radius) * sp.n_geo;
  sp.n_shade = sp.n_geo;
  sp.material = s.material;
  return sp;
}

SurfacePoint on_triangle(const Geometry& g, const Triangle& tri, const Ray& ray) {
  SurfacePoint sp;
  float u = 0.0f, v = 0.0f;
  intersect_triangle(tri.p0, tri.p1, tri.p2, ray, &u, &v);
  const float w = 1.0f - u - v;
  sp.p = w * tri.p0 + u * tri.p1 + v * tri.p2;  // barycentric: exact to the vertices' ulps
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
  // Snap the coordinate across the face onto the face itself.
  for (int a = 0; a < 3; ++a)
    if (sp.n_geo[a] != 0.0f) sp.p[a] = sp.n_geo[a] > 0.0f ? box.hi[a] : box.lo[a];
  sp.n_shade = sp.n_geo;
  sp.material = box.material;
  return sp;
}

SurfacePoint on_plane(const Plane& pl, const Ray& ray, float t) {
  SurfacePoint sp;
  sp.p = ray.org + t * ray.dir;
  sp.p -= (glm::dot(pl.normal, sp.p) - pl.offset) * pl.normal;
  sp.n_geo = pl.normal;
  sp.n_shade = pl.normal;
  sp.material = pl.material;
  return sp;
}

SurfacePoint on_cone(const Cone& c, const Ray& ray, float t) {
  SurfacePoint sp;
  sp.p = ray.org + t * ray.dir;
  sp.n_geo = normal_at(c, sp.p);
  sp.n_shade = sp.n_geo;
  sp.material = c.material;
  return sp;
}

SurfacePoint on_polygon(const Geometry& g, const Polygon& poly, const Ray& ray, float t) {
  SurfacePoint sp;
  sp.p = ray.org + t * ray.dir;
  const float offset = glm::dot(poly.normal, g.polygon_vertices[poly.first_vertex]);
  sp.p -= (glm::dot(poly.normal, sp.p) - offset) * poly.normal;
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
