// N spheres at uniform random positions in a 10-unit cube. Their radii shrink as N grows
// (0.1 to 0.3 of the mean spacing 10 / cbrt(N)), so the cube looks equally full at any N; at
// N = 8000 the radii match spheres8000's 0.05 to 0.15. Spheres may overlap.

#include "framing.h"
#include "materials.h"
#include "generator_functions.h"
#include "rng.h"

#include <cmath>

namespace scenes_gen {

tracer::Scene make_random(const GenOptions& options) {
  constexpr int kDefaultCount = 1000;
  constexpr float kCube = 10.0f;
  const int count = options.count.value_or(kDefaultCount);
  tracer::Scene scene;
  scene.materials = {
      diffuse("red", {0.8f, 0.2f, 0.15f}, 0.2f), diffuse("green", {0.25f, 0.7f, 0.3f}, 0.2f),
      diffuse("blue", {0.2f, 0.35f, 0.85f}, 0.2f), diffuse("white", {0.8f, 0.8f, 0.8f}, 0.2f)};
  const float spacing = kCube / std::cbrt(float(std::max(count, 1)));
  Rng rng(options.seed);
  scene.geometry.spheres.reserve(std::size_t(count));
  for (int i = 0; i < count; ++i) {
    tracer::Sphere s;
    s.center = {rng.uniform(-0.5f * kCube, 0.5f * kCube), rng.uniform(-0.5f * kCube, 0.5f * kCube),
                rng.uniform(-0.5f * kCube, 0.5f * kCube)};
    s.radius = spacing * rng.uniform(0.1f, 0.3f);
    s.material = rng.below(4);
    scene.geometry.spheres.push_back(s);
  }
  const accel::Aabb bounds{tracer::Vec3(-0.5f * kCube), tracer::Vec3(0.5f * kCube)};
  scene.camera = frame_bounds(bounds, tracer::Vec3(1.0f, 0.8f, 1.3f));
  scene.lights = {point_light({12.0f, 18.0f, 14.0f}, 30000.0f),
                  point_light({-16.0f, 6.0f, 12.0f}, 12000.0f)};
  scene.background = {0.02f, 0.02f, 0.05f};
  return scene;
}

}  // namespace scenes_gen
