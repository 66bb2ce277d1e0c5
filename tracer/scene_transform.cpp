#include "scene_transform.h"

#include <glm/vec3.hpp>

namespace tracer {

namespace {

/// p + offset with one rounding to float (the sum is exact in double for every float p and
/// offset of the same magnitude; one rounding is what a scene stored there would hold).
Vec3 moved(const Vec3& p, const glm::dvec3& offset) { return Vec3(glm::dvec3(p) + offset); }

Vec3 scaled(const Vec3& p, double factor) { return Vec3(glm::dvec3(p) * factor); }

template <class Fn>
void for_each_position(Scene& scene, Fn&& fn) {
  // Moved triangles no longer match their model files: a saved copy writes them out in full.
  scene.meshes.clear();
  scene.camera.position = fn(scene.camera.position);
  scene.camera.look_at = fn(scene.camera.look_at);
  for (PointLight& l : scene.lights) l.position = fn(l.position);
  Geometry& g = scene.geometry;
  for (Sphere& s : g.spheres) s.center = fn(s.center);
  for (Triangle& t : g.triangles) {
    t.p0 = fn(t.p0);
    t.p1 = fn(t.p1);
    t.p2 = fn(t.p2);
  }
  for (Box& b : g.boxes) {
    b.lo = fn(b.lo);
    b.hi = fn(b.hi);
  }
  for (Cone& c : g.cones) c.base = fn(c.base);
  for (Vec3& v : g.polygon_vertices) v = fn(v);
}

}  // namespace

void translate_scene(Scene& scene, const glm::dvec3& offset) {
  for_each_position(scene, [&](const Vec3& p) { return moved(p, offset); });
  for (Plane& pl : scene.geometry.planes)
    pl.offset = float(double(pl.offset) + glm::dot(glm::dvec3(pl.normal), offset));
}

void scale_scene(Scene& scene, double factor) {
  for_each_position(scene, [&](const Vec3& p) { return scaled(p, factor); });
  Geometry& g = scene.geometry;
  for (Sphere& s : g.spheres) s.radius = float(double(s.radius) * factor);
  for (Cone& c : g.cones) {
    c.base_radius = float(double(c.base_radius) * factor);
    c.apex_radius = float(double(c.apex_radius) * factor);
    c.height = float(double(c.height) * factor);
  }
  for (Plane& pl : g.planes) pl.offset = float(double(pl.offset) * factor);
  scene.camera.hither = float(double(scene.camera.hither) * factor);
  for (PointLight& l : scene.lights) l.power_w = float(double(l.power_w) * factor * factor);
  for (Material& m : scene.materials) m.absorption = Color(glm::dvec3(m.absorption) / factor);
}

glm::dvec3 primitive_centre(const Geometry& g, std::uint32_t id) {
  using glm::dvec3;
  switch (g.kind_of(id)) {
    case PrimitiveKind::Sphere:
      return dvec3(g.spheres[id - g.first_id[0]].center);
    case PrimitiveKind::Triangle: {
      const Triangle& t = g.triangles[id - g.first_id[1]];
      return (dvec3(t.p0) + dvec3(t.p1) + dvec3(t.p2)) / 3.0;
    }
    case PrimitiveKind::Box: {
      const Box& b = g.boxes[id - g.first_id[2]];
      return 0.5 * (dvec3(b.lo) + dvec3(b.hi));
    }
    case PrimitiveKind::Cone: {
      const Cone& c = g.cones[id - g.first_id[3]];
      return dvec3(c.base) + 0.5 * double(c.height) * dvec3(c.axis);
    }
    case PrimitiveKind::Polygon: {
      const Polygon& p = g.polygons[id - g.first_id[4]];
      dvec3 sum(0.0);
      for (std::uint32_t i = 0; i < p.vertex_count; ++i)
        sum += dvec3(g.polygon_vertices[p.first_vertex + i]);
      return sum / double(p.vertex_count);
    }
    case PrimitiveKind::Count:
      break;
  }
  return dvec3(0.0);
}

void move_primitive(Geometry& g, std::uint32_t id, const glm::dvec3& delta) {
  switch (g.kind_of(id)) {
    case PrimitiveKind::Sphere: {
      Sphere& s = g.spheres[id - g.first_id[0]];
      s.center = moved(s.center, delta);
      break;
    }
    case PrimitiveKind::Triangle: {
      Triangle& t = g.triangles[id - g.first_id[1]];
      t.p0 = moved(t.p0, delta);
      t.p1 = moved(t.p1, delta);
      t.p2 = moved(t.p2, delta);
      break;
    }
    case PrimitiveKind::Box: {
      Box& b = g.boxes[id - g.first_id[2]];
      b.lo = moved(b.lo, delta);
      b.hi = moved(b.hi, delta);
      break;
    }
    case PrimitiveKind::Cone: {
      Cone& c = g.cones[id - g.first_id[3]];
      c.base = moved(c.base, delta);
      break;
    }
    case PrimitiveKind::Polygon: {
      const Polygon& p = g.polygons[id - g.first_id[4]];
      for (std::uint32_t i = 0; i < p.vertex_count; ++i)
        g.polygon_vertices[p.first_vertex + i] = moved(g.polygon_vertices[p.first_vertex + i], delta);
      break;
    }
    case PrimitiveKind::Count:
      break;
  }
}

void append_copies(Geometry& g, const std::vector<glm::dvec3>& shifts, bool copy_planes) {
  const Geometry original = g;
  const std::uint32_t n = original.bounded_count();
  // Per kind, append the copies right after the originals; then move each copy by its shift.
  g.spheres.insert(g.spheres.end(), original.spheres.begin(), original.spheres.end());
  g.triangles.insert(g.triangles.end(), original.triangles.begin(), original.triangles.end());
  g.boxes.insert(g.boxes.end(), original.boxes.begin(), original.boxes.end());
  g.cones.insert(g.cones.end(), original.cones.begin(), original.cones.end());
  for (const Polygon& p : original.polygons) {
    Polygon copy = p;
    copy.first_vertex = std::uint32_t(g.polygon_vertices.size());
    for (std::uint32_t i = 0; i < p.vertex_count; ++i)
      g.polygon_vertices.push_back(original.polygon_vertices[p.first_vertex + i]);
    g.polygons.push_back(copy);
  }
  if (copy_planes) g.planes.insert(g.planes.end(), original.planes.begin(), original.planes.end());
  g.finalize();
  for (std::uint32_t id = 0; id < n && id < shifts.size(); ++id) {
    // The copy of original id k of kind K sits at first_id[K] + count[K] + (k - original first).
    const auto kind = std::size_t(original.kind_of(id));
    const std::uint32_t local = id - original.first_id[kind];
    const std::uint32_t count = original.first_id[kind + 1] - original.first_id[kind];
    const std::uint32_t copy = g.first_id[kind] + count + local;
    if (shifts[id] != glm::dvec3(0.0)) move_primitive(g, copy, shifts[id]);
  }
}

}  // namespace tracer
