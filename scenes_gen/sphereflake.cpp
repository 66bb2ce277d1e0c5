#include "sphereflake.h"

#include "framing.h"

#include "tracer/orthonormal_basis.h"

#include <glm/geometric.hpp>

#include <array>
#include <cmath>
#include <string>

namespace scenes_gen {
namespace {

using tracer::Vec3;

constexpr float kPi = 3.14159265358979f;

/// The nine child directions in a frame whose z is the parent-to-sphere axis: six around the
/// equator every 60 degrees and three at 60 degrees elevation between them, as in SPD "balls".
std::array<Vec3, 9> child_directions_local() {
  std::array<Vec3, 9> d;
  for (int k = 0; k < 6; ++k) {
    const float phi = float(k) * kPi / 3.0f;
    d[std::size_t(k)] = Vec3(std::cos(phi), std::sin(phi), 0.0f);
  }
  const float elev = kPi / 3.0f;
  for (int k = 0; k < 3; ++k) {
    const float phi = kPi / 6.0f + float(k) * 2.0f * kPi / 3.0f;
    d[std::size_t(6 + k)] =
        Vec3(std::cos(elev) * std::cos(phi), std::cos(elev) * std::sin(phi), std::sin(elev));
  }
  return d;
}

void add_flake(tracer::Geometry& g, const Vec3& centre, float radius, const Vec3& axis, int levels_left,
               const std::array<Vec3, 9>& local) {
  g.spheres.push_back({centre, radius, 0});
  if (levels_left == 0) return;
  Vec3 x, y;
  tracer::orthonormal_basis(axis, x, y);  // a right-handed frame with z = axis
  const float child_radius = radius / 3.0f;
  for (const Vec3& l : local) {
    const Vec3 dir = glm::normalize(l.x * x + l.y * y + l.z * axis);
    add_flake(g, centre + dir * (radius + child_radius), child_radius, dir, levels_left - 1, local);
  }
}

}  // namespace

long long sphereflake_sphere_count(int size) {
  long long total = 0, level = 1;
  for (int i = 0; i <= size; ++i, level *= 9) total += level;
  return total;
}

tracer::Scene make_sphereflake(const GenOptions& options) {
  const int size = options.count.value_or(kSphereflakeDefaultSize);
  if (size < kSphereflakeMinSize || size > kSphereflakeMaxSize)
    throw GenError("sphereflake: size factor must be in [" + std::to_string(kSphereflakeMinSize) +
                                ", " + std::to_string(kSphereflakeMaxSize) + "], got " + std::to_string(size));
  tracer::Scene scene;
  tracer::Material shiny;
  shiny.name = "flake";
  shiny.albedo = {0.85f, 0.6f, 0.45f};
  shiny.specular = 0.5f;
  shiny.shininess = 40.0f;
  scene.materials.push_back(shiny);

  scene.geometry.spheres.reserve(std::size_t(sphereflake_sphere_count(size)));
  add_flake(scene.geometry, Vec3(0.0f), 0.5f, Vec3(0.0f, 0.0f, 1.0f), size, child_directions_local());
  scene.geometry.finalize();

  accel::Aabb bounds;
  for (const auto& b : scene.geometry.primitive_bounds()) bounds.grow(b);
  // SPD balls' view: eye at (2.1, 1.3, 1.7) looking at the origin, z up.
  scene.camera = frame_bounds(bounds, Vec3(2.1f, 1.3f, 1.7f), Vec3(0.0f, 0.0f, 1.0f), 45.0f);
  // SPD balls' three lights, around the flake.
  const Vec3 centre = 0.5f * (bounds.lo + bounds.hi);
  for (const Vec3& p : {Vec3(4.0f, 3.0f, 2.0f), Vec3(1.0f, -4.0f, 4.0f), Vec3(-3.0f, 1.0f, 5.0f)})
    scene.lights.push_back(light_at(centre, p, 1.0f, 450.0f));
  scene.background = {0.08f, 0.1f, 0.16f};
  return scene;
}

}  // namespace scenes_gen
