// The paper's Figure 8: five spheres, a glass one in the middle between a mirror and three
// diffuse ones, standing on a floor (an unbounded plane, so the structures still hold five).

#include "materials.h"
#include "generator_functions.h"

namespace scenes_gen {

tracer::Scene make_five(const GenOptions&) {
  tracer::Scene scene;
  scene.materials = {glass("glass", 1.5f),
                     mirror("mirror", {0.9f, 0.9f, 0.9f}),
                     diffuse("red", {0.8f, 0.12f, 0.1f}, 0.4f, 64.0f),
                     diffuse("blue", {0.1f, 0.25f, 0.8f}, 0.4f, 64.0f),
                     diffuse("gold", {0.85f, 0.65f, 0.2f}, 0.6f, 128.0f),
                     diffuse("floor", {0.5f, 0.5f, 0.48f})};
  auto& s = scene.geometry.spheres;
  s.push_back({{0.0f, 1.0f, 0.0f}, 1.0f, 0});
  s.push_back({{-2.3f, 0.9f, -1.2f}, 0.9f, 1});
  s.push_back({{2.3f, 0.9f, -1.2f}, 0.9f, 2});
  s.push_back({{-1.3f, 0.45f, 1.7f}, 0.45f, 3});
  s.push_back({{1.3f, 0.45f, 1.7f}, 0.45f, 4});
  scene.geometry.planes.push_back({{0.0f, 1.0f, 0.0f}, 0.0f, 5});
  scene.lights = {point_light({-4.0f, 6.0f, 6.0f}, 3000.0f),
                  point_light({5.0f, 4.0f, 3.0f}, 1200.0f),
                  point_light({0.5f, 3.0f, 9.0f}, 600.0f)};
  scene.background = {0.35f, 0.45f, 0.6f};
  scene.camera.position = {0.0f, 2.2f, 7.5f};
  scene.camera.look_at = {0.0f, 0.7f, 0.0f};
  scene.camera.vfov_deg = 40.0f;
  scene.camera.width = 640;
  scene.camera.height = 480;
  scene.render.max_depth = 10;
  return scene;
}

}  // namespace scenes_gen
