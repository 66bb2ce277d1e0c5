// Scenes for photon mapping. Each picks the photon integrator in its "integrator" object (the
// command line may still choose another) with photon counts that show its effect at the default
// image size in seconds.

#include "photon_scenes.h"

#include "framing.h"
#include "generator_functions.h"
#include "materials.h"
#include "mesh_scenes.h"

#include "photon/photon_integrator.h"
#include "photon/photon_params.h"

#include <cmath>
#include <numbers>
#include <optional>
#include <string>

namespace scenes_gen {

namespace {

using tracer::Vec3;

/// A quad as two triangles, corners counter-clockwise seen from the side its normal faces.
void add_quad(tracer::Geometry& g, Vec3 a, Vec3 b, Vec3 c, Vec3 d, std::uint32_t material) {
  g.triangles.push_back({a, b, c, material, -1});
  g.triangles.push_back({a, c, d, material, -1});
}

/// Picks the photon integrator with the knobs of `p` that differ from the defaults.
void choose_photon(tracer::Scene& scene, const photon::PhotonParams& p) {
  scene.integrator.name = std::string(photon::photon_integrator().name);
  scene.integrator.knobs = photon::PhotonParams::knobs().changed_json(p);
}

/// Photon knobs: the counts of the two maps and the gather.
photon::PhotonParams photon_knobs(int caustic, int global, int k, std::optional<float> max_radius) {
  photon::PhotonParams p;
  p.caustic_photons = caustic;
  p.global_photons = global;
  p.k = k;
  p.max_radius = max_radius;
  return p;
}

}  // namespace

// The paper's Figure 4: a mirror ring (a cylinder shell without caps, reflective on both sides)
// on a diffuse floor, lit from the side by one point light over its rim. Light reflected off the
// inside of the far wall converges into the cardioid (nephroid) caustic on the floor inside.
tracer::Scene make_ring(const GenOptions&) {
  tracer::Scene scene;
  scene.materials = {mirror("ring", {0.95f, 0.9f, 0.75f}), diffuse("floor", {0.75f, 0.75f, 0.72f})};
  scene.geometry.cones.push_back(
      tracer::make_cone({0.0f, 0.0f, 0.0f}, 1.0f, {0.0f, 0.6f, 0.0f}, 1.0f, 0));
  scene.geometry.planes.push_back({Vec3(0.0f, 1.0f, 0.0f), 0.0f, 1});
  scene.lights = {point_light({-6.0f, 2.2f, 0.0f}, 1500.0f)};
  scene.background = {0.0f, 0.0f, 0.0f};
  scene.camera.position = {0.5f, 3.3f, 1.9f};
  scene.camera.look_at = {0.1f, 0.0f, -0.05f};
  scene.camera.vfov_deg = 40.0f;
  scene.camera.width = 480;
  scene.camera.height = 360;
  scene.render.max_depth = 8;
  // The floor is unbounded and nothing stands over it but the ring: few photons bounce back
  // down after a diffuse bounce, so the global map is small (its pass stops at its cap).
  choose_photon(scene, photon_knobs(200000, 2000, 80, 0.08f));
  return scene;
}

// The paper's Figure 5: a glass sphere focusing a point light into a bright caustic on the
// diffuse floor beside its shadow.
tracer::Scene make_glass_caustic(const GenOptions&) {
  tracer::Scene scene;
  scene.materials = {glass("glass", 1.5f), diffuse("floor", {0.7f, 0.7f, 0.68f}),
                     diffuse("wall", {0.6f, 0.62f, 0.7f})};
  // A ball lens of radius 1 and index 1.5 focuses at n R / (2 (n - 1)) = 1.5 from its centre for
  // parallel light; for the light 6.5 away the image lies about 1.95 from the centre, which the
  // sphere's height puts on the floor.
  scene.geometry.spheres.push_back({{0.0f, 1.8f, 0.0f}, 1.0f, 0});
  scene.geometry.planes.push_back({Vec3(0.0f, 1.0f, 0.0f), 0.0f, 1});
  scene.geometry.planes.push_back({Vec3(0.0f, 0.0f, 1.0f), -4.0f, 2});  // z = -4
  scene.lights = {point_light({-2.0f, 8.0f, 0.6f}, 1800.0f)};
  scene.background = {0.0f, 0.0f, 0.0f};
  scene.camera.position = {0.0f, 3.4f, 6.5f};
  scene.camera.look_at = {0.4f, 0.9f, 0.0f};
  scene.camera.vfov_deg = 42.0f;
  scene.camera.width = 480;
  scene.camera.height = 360;
  scene.render.max_depth = 10;
  choose_photon(scene, photon_knobs(200000, 100000, 150, 0.6f));
  return scene;
}

// A Cornell box (red left wall, green right wall, white floor, ceiling and back) lit by one point
// light under the ceiling, with a mirror sphere and a glass sphere: colour bleeding in the global
// map, caustics under the glass sphere in the caustic map.
tracer::Scene make_cornell(const GenOptions&) {
  tracer::Scene scene;
  scene.materials = {diffuse("white", {0.73f, 0.73f, 0.73f}), diffuse("red", {0.63f, 0.07f, 0.05f}),
                     diffuse("green", {0.12f, 0.45f, 0.09f}), mirror("mirror", {0.9f, 0.9f, 0.9f}),
                     glass("glass", 1.5f)};
  enum : std::uint32_t { kWhite, kRed, kGreen, kMirror, kGlass };
  tracer::Geometry& g = scene.geometry;
  const float s = 1.0f;  // half width; the box is [-1, 1] x [0, 2] x [-1, 1], open at z = +1
  add_quad(g, {-s, 0, -s}, {-s, 0, s}, {s, 0, s}, {s, 0, -s}, kWhite);                // floor
  add_quad(g, {-s, 2 * s, -s}, {s, 2 * s, -s}, {s, 2 * s, s}, {-s, 2 * s, s}, kWhite); // ceiling
  add_quad(g, {-s, 0, -s}, {s, 0, -s}, {s, 2 * s, -s}, {-s, 2 * s, -s}, kWhite);      // back
  add_quad(g, {-s, 0, -s}, {-s, 2 * s, -s}, {-s, 2 * s, s}, {-s, 0, s}, kRed);        // left
  add_quad(g, {s, 0, -s}, {s, 0, s}, {s, 2 * s, s}, {s, 2 * s, -s}, kGreen);          // right
  g.spheres.push_back({{-0.45f, 0.35f, -0.35f}, 0.35f, kMirror});
  g.spheres.push_back({{0.45f, 0.35f, 0.25f}, 0.35f, kGlass});
  scene.lights = {point_light({0.0f, 1.8f, 0.0f}, 50.0f)};
  scene.background = {0.0f, 0.0f, 0.0f};
  scene.camera.position = {0.0f, 1.0f, 3.9f};
  scene.camera.look_at = {0.0f, 1.0f, 0.0f};
  scene.camera.vfov_deg = 38.0f;
  scene.camera.width = 400;
  scene.camera.height = 400;
  scene.render.max_depth = 10;
  // The global map is read directly (final gathering is a knob away, and slower: its rays that
  // meet the ceiling near the light bring back fireflies at few rays).
  choose_photon(scene, photon_knobs(100000, 200000, 200, 0.3f));
  return scene;
}

tracer::Scene make_furnace_scene(float radius, float albedo, float power_w) {
  tracer::Scene scene;
  scene.materials = {diffuse("wall", {albedo, albedo, albedo})};
  // Only the inside is visible (NFF's negative radius): the light and the camera are inside.
  scene.geometry.spheres.push_back({{0.0f, 0.0f, 0.0f}, -radius, 0});
  scene.lights = {point_light({0.0f, 0.0f, 0.0f}, power_w)};
  scene.background = {0.0f, 0.0f, 0.0f};
  scene.camera.position = {0.0f, 0.0f, 0.0f};
  scene.camera.look_at = {0.0f, 0.0f, -1.0f};
  scene.camera.vfov_deg = 90.0f;
  scene.camera.width = 64;
  scene.camera.height = 64;
  scene.render.max_depth = 4;
  photon::PhotonParams knobs = photon_knobs(photon::PhotonParams{}.caustic_photons, 100000, 100, std::nullopt);
  knobs.max_photon_depth = 1000;
  choose_photon(scene, knobs);
  scene.geometry.finalize();
  return scene;
}

tracer::Scene make_furnace(const GenOptions&) {
  return make_furnace_scene(1.0f, 0.5f, 100.0f);
}

// A model (the Stanford bunny by default) in glass on a diffuse floor, lit by one point light low
// at its side: its shadow falls long across the floor, and the light the glass refracts gathers
// into caustics inside it. The model keeps its own coordinates; light, camera and photon radius
// follow its size as the glass sphere's of Figure 5 do (radius 1, power 1800 W, max_radius 0.6).
tracer::Scene make_mesh_caustic(const GenOptions& options) {
  tracer::Scene scene = scene_around_model(model_path(options.model.empty() ? "bunny" : options.model));
  accel::Aabb bounds;
  for (const tracer::Triangle& t : scene.geometry.triangles)
    for (const Vec3& p : {t.p0, t.p1, t.p2}) bounds.grow(p);
  const float size = std::max(glm::length(bounds.extent()), 1e-6f);
  const float unit = size / 3.46f;  // Figure 5's glass sphere has a bounding-box diagonal of 3.46
  scene.materials[0] = glass("glass", 1.5f);
  scene.materials[1] = diffuse("floor", {0.7f, 0.7f, 0.68f});
  const Vec3 centre = bounds.center();
  scene.lights = {light_at(centre, {-3.5f, 2.6f, 1.2f}, unit, 1800.0f)};
  scene.background = {0.0f, 0.0f, 0.0f};
  // The floor beyond the model on the side away from the light, where the caustic falls.
  accel::Aabb view = bounds;
  view.grow(Vec3(bounds.hi.x + 2.0f * unit, bounds.lo.y, bounds.center().z - 0.8f * unit));
  scene.camera = frame_bounds(view, Vec3(0.15f, 0.55f, 1.0f));
  scene.camera.width = 480;
  scene.camera.height = 360;
  scene.render.max_depth = 10;
  // Few global photons: on an open floor under an open sky most global paths leave the scene
  // without a stored photon (100,000 would take 25 million paths and seconds).
  choose_photon(scene, photon_knobs(200000, 20000, 150, 0.6f * unit));
  return scene;
}

}  // namespace scenes_gen
