#include "harness/analytic_reference.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>

namespace harness {

std::optional<tracer::Color> furnace_radiance(const tracer::Scene& scene) {
  const tracer::Geometry& g = scene.geometry;
  if (g.spheres.size() != 1 || !g.triangles.empty() || !g.boxes.empty() || !g.cones.empty() || !g.polygons.empty() ||
      !g.planes.empty() || scene.lights.empty())
    return std::nullopt;
  const tracer::Sphere& s = g.spheres[0];
  if (s.material >= scene.materials.size()) return std::nullopt;
  const tracer::Material& m = scene.materials[s.material];
  if (m.type != tracer::MaterialType::Diffuse || m.specular != 0.0f) return std::nullopt;
  const double r = std::abs(double(s.radius));
  if (!(r > 0.0) || !(glm::length(scene.camera.position - s.center) < float(r))) return std::nullopt;
  glm::dvec3 power(0.0);
  for (const tracer::PointLight& l : scene.lights) {
    if (l.position != s.center) return std::nullopt;
    power += double(l.power_w) * glm::dvec3(l.color);
  }
  tracer::Color out;
  for (int c = 0; c < 3; ++c) {
    const double rho = m.albedo[c];
    if (!(rho >= 0.0 && rho < 1.0)) return std::nullopt;
    out[c] = float(rho * power[c] / (4.0 * std::numbers::pi * std::numbers::pi * r * r * (1.0 - rho)));
  }
  return out;
}

tracer::Image uniform_image(const tracer::Color& radiance, int width, int height) {
  tracer::Image image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) image.at(x, y) = radiance;
  return image;
}

}  // namespace harness
