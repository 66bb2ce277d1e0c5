#include "map_needs.h"

#include <algorithm>
#include <vector>

namespace photon {

namespace {

float max_channel(const tracer::Color& c) { return std::max(c.x, std::max(c.y, c.z)); }

/// Calls fn(material index) for every primitive, bounded ones with their box.
template <class Fn>
void for_each_primitive(const tracer::Scene& scene, Fn&& fn) {
  const tracer::Geometry& g = scene.geometry;
  const std::vector<accel::Aabb> boxes = g.primitive_bounds();
  std::uint32_t id = 0;
  for (const auto& s : g.spheres) fn(s.material, &boxes[id++]);
  for (const auto& t : g.triangles) fn(t.material, &boxes[id++]);
  for (const auto& b : g.boxes) fn(b.material, &boxes[id++]);
  for (const auto& c : g.cones) fn(c.material, &boxes[id++]);
  for (const auto& p : g.polygons) fn(p.material, &boxes[id++]);
  for (const auto& p : g.planes) fn(p.material, static_cast<const accel::Aabb*>(nullptr));
}

}  // namespace

MaterialRole role_of(const tracer::Material& m) {
  MaterialRole r;
  switch (m.type) {
    case tracer::MaterialType::Diffuse:
      r.diffuse = true;
      r.reflects = max_channel(m.albedo) > 0.0f;
      break;
    case tracer::MaterialType::Mirror:
      r.specular = max_channel(m.reflectance) > 0.0f;
      break;
    case tracer::MaterialType::Dielectric:
      r.specular = true;
      break;
    case tracer::MaterialType::Nff:
      r.specular = m.ks > 0.0f || m.transmittance > 0.0f;
      r.diffuse = true;
      r.reflects = m.kd * max_channel(m.albedo) > 0.0f;
      break;
  }
  return r;
}

SpecularBounds specular_bounds(const tracer::Scene& scene) {
  SpecularBounds b;
  for_each_primitive(scene, [&](std::uint32_t material, const accel::Aabb* box) {
    if (!role_of(scene.materials[material]).specular) return;
    if (box)
      b.box.grow(*box);
    else
      b.all = true;
  });
  return b;
}

MapNeeds map_needs(const tracer::Scene& scene) {
  MapNeeds n;
  bool light = false;
  for (const tracer::PointLight& l : scene.lights)
    light = light || (l.power_w > 0.0f && max_channel(l.color) > 0.0f);
  bool specular = false, reflects = false;
  for_each_primitive(scene, [&](std::uint32_t material, const accel::Aabb*) {
    const MaterialRole r = role_of(scene.materials[material]);
    specular = specular || r.specular;
    reflects = reflects || r.reflects;
  });
  if (!light) {
    n.caustic_reason = n.global_reason = "no light emits";
    return n;
  }
  n.global = reflects;
  if (!reflects) n.global_reason = "no diffuse surface reflects light (albedo > 0)";
  n.caustic = specular && reflects;
  if (!specular)
    n.caustic_reason = "no specular surface";
  else if (!reflects)
    n.caustic_reason = "no diffuse surface reflects light (albedo > 0)";
  return n;
}

}  // namespace photon
