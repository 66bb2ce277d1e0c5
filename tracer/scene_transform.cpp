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

}  // namespace tracer
