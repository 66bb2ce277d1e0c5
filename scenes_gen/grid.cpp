#include "grid.h"

#include "framing.h"

#include <cmath>
#include <string>

namespace scenes_gen {

tracer::Scene make_grid(const GenOptions& options) {
  const int count = options.count.value_or(kGridDefaultCount);
  if (count < 0) throw GenError("grid: count must be >= 0, got " + std::to_string(count));
  tracer::Scene scene;
  tracer::Material matte;
  matte.name = "matte";
  matte.albedo = {0.7f, 0.75f, 0.8f};
  matte.specular = 0.3f;
  scene.materials.push_back(matte);

  int side = 1;
  while (side * side * side < count) ++side;
  const float offset = 0.5f * float(side - 1);
  auto& spheres = scene.geometry.spheres;
  spheres.reserve(std::size_t(count));
  for (int i = 0; i < count; ++i) {
    const int x = i % side, y = (i / side) % side, z = i / (side * side);
    spheres.push_back({tracer::Vec3(float(x) - offset, float(y) - offset, float(z) - offset), 0.35f, 0});
  }
  scene.geometry.finalize();

  const float half = 0.5f * float(side);
  const accel::Aabb bounds{tracer::Vec3(-half), tracer::Vec3(half)};
  scene.camera = frame_bounds(bounds, tracer::Vec3(0.6f, 0.5f, 1.0f));
  scene.lights.push_back(light_at(tracer::Vec3(0.0f), tracer::Vec3(1.0f, 2.0f, 1.5f), float(side), 110.0f));
  scene.lights.push_back(light_at(tracer::Vec3(0.0f), tracer::Vec3(-1.5f, 1.0f, 2.0f), float(side), 50.0f));
  scene.background = {0.05f, 0.05f, 0.08f};
  return scene;
}

}  // namespace scenes_gen
