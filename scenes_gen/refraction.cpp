// The paper's Figure 1: a glass bar standing before a checkered wall, turned so that the light
// bends visibly at its edges: the checks seen through the bar are shifted against those beside
// it, and the bar's side faces show them squeezed, mirrored by total internal reflection.

#include "materials.h"
#include "generator_functions.h"

#include <cmath>

namespace scenes_gen {

namespace {

using tracer::Vec3;

/// Twelve outward-wound triangles of a box of half-extents `half` centred at `centre`, turned
/// by `yaw_deg` about the vertical axis.
void add_turned_box(tracer::Geometry& g, Vec3 centre, Vec3 half, float yaw_deg,
                    std::uint32_t material) {
  const float a = yaw_deg * 3.14159265f / 180.0f;
  const float c = std::cos(a), s = std::sin(a);
  auto corner = [&](int i) {
    const Vec3 p((i & 1 ? 1.0f : -1.0f) * half.x, (i & 2 ? 1.0f : -1.0f) * half.y,
                 (i & 4 ? 1.0f : -1.0f) * half.z);
    return centre + Vec3(c * p.x + s * p.z, p.y, -s * p.x + c * p.z);
  };
  // Each face as four corner indices, counter-clockwise seen from outside.
  constexpr int kFaces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& f : kFaces) {
    g.triangles.push_back({corner(f[0]), corner(f[1]), corner(f[2]), material, -1});
    g.triangles.push_back({corner(f[0]), corner(f[2]), corner(f[3]), material, -1});
  }
}

}  // namespace

tracer::Scene make_refraction(const GenOptions&) {
  tracer::Scene scene;
  scene.materials = {diffuse("white", {0.85f, 0.85f, 0.82f}), diffuse("dark", {0.08f, 0.1f, 0.3f}),
                     diffuse("floor", {0.45f, 0.42f, 0.38f}),
                     glass("glass", 1.5f, {0.02f, 0.01f, 0.03f})};
  enum : std::uint32_t { kWhite, kDark, kFloor, kGlass };

  // The wall: 24 x 12 checks of 0.5 units, thin boxes standing on the floor.
  constexpr float kCheck = 0.5f;
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 24; ++i) {
      const Vec3 lo(-6.0f + kCheck * float(i), kCheck * float(j), -3.1f);
      scene.geometry.boxes.push_back(
          {lo, lo + Vec3(kCheck, kCheck, 0.1f), (i + j) % 2 ? kDark : kWhite});
    }
  scene.geometry.planes.push_back({Vec3(0.0f, 1.0f, 0.0f), 0.0f, kFloor});
  // The bar stands 0.02 above the floor: a bottom face coplanar with the floor would flicker.
  add_turned_box(scene.geometry, Vec3(0.0f, 1.62f, 0.5f), Vec3(0.45f, 1.6f, 0.45f), 30.0f, kGlass);

  scene.lights = {point_light({-3.0f, 7.0f, 6.0f}, 2500.0f),
                  point_light({4.0f, 5.0f, 7.0f}, 1200.0f)};
  scene.background = {0.6f, 0.7f, 0.9f};
  scene.camera.position = {0.0f, 2.0f, 8.0f};
  scene.camera.look_at = {0.0f, 1.6f, 0.0f};
  scene.camera.vfov_deg = 35.0f;
  scene.camera.width = 800;
  scene.camera.height = 600;
  scene.camera.samples_per_pixel = 4;
  scene.render.max_depth = 10;
  return scene;
}

}  // namespace scenes_gen
