// The paper's Figure 7: 8000 spheres on a jittered 20 x 20 x 20 grid filling a 10-unit cube,
// radii 0.05 to 0.15, each inside its own 0.5-unit cell so that none overlap.

#include "framing.h"
#include "materials.h"
#include "generator_functions.h"
#include "rng.h"

namespace scenes_gen {

tracer::Scene make_spheres8000(const GenOptions& options) {
  tracer::Scene scene;
  scene.materials = {
      diffuse("red", {0.8f, 0.15f, 0.1f}, 0.3f),    diffuse("orange", {0.9f, 0.5f, 0.1f}, 0.3f),
      diffuse("yellow", {0.85f, 0.8f, 0.2f}, 0.3f), diffuse("green", {0.2f, 0.7f, 0.25f}, 0.3f),
      diffuse("blue", {0.15f, 0.3f, 0.85f}, 0.3f),  diffuse("white", {0.8f, 0.8f, 0.8f}, 0.3f),
      mirror("mirror", {0.9f, 0.9f, 0.9f}),         glass("glass", 1.5f)};
  constexpr int kSide = 20;
  constexpr float kCube = 10.0f, kCell = kCube / kSide;
  Rng rng(options.seed);
  for (int z = 0; z < kSide; ++z)
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x) {
        tracer::Sphere s;
        s.radius = rng.uniform(0.05f, 0.15f);
        const float room = 0.5f * kCell - s.radius;  // jitter that keeps the sphere in its cell
        const tracer::Vec3 cell_centre =
            -0.5f * kCube + kCell * (tracer::Vec3(float(x), float(y), float(z)) + 0.5f);
        // Drawn z, y, x: the order gcc evaluated the three calls in when they were a constructor's
        // arguments (an order C++ leaves unspecified; clang took x first and drew another scene).
        // Named and sequenced, every compiler draws the scene every published figure used.
        const float dz = rng.uniform(-room, room), dy = rng.uniform(-room, room), dx = rng.uniform(-room, room);
        s.center = cell_centre + tracer::Vec3(dx, dy, dz);
        const float pick = rng.uniform();  // 80% diffuse, 10% mirror, 10% glass
        s.material = pick < 0.8f ? rng.below(6) : (pick < 0.9f ? 6u : 7u);
        scene.geometry.spheres.push_back(s);
      }
  const accel::Aabb bounds{tracer::Vec3(-0.5f * kCube), tracer::Vec3(0.5f * kCube)};
  scene.camera = frame_bounds(bounds, tracer::Vec3(1.0f, 0.8f, 1.3f));
  scene.camera.width = 800;
  scene.camera.height = 600;
  scene.lights = {point_light({12.0f, 18.0f, 14.0f}, 30000.0f),
                  point_light({-16.0f, 6.0f, 12.0f}, 12000.0f),
                  point_light({6.0f, -10.0f, 16.0f}, 6000.0f)};
  scene.background = {0.02f, 0.02f, 0.05f};
  scene.render.max_depth = 6;
  return scene;
}

}  // namespace scenes_gen
