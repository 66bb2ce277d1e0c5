// The Whitted integrator against scenes whose answer is known.

#include "tracer/render.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using tracer::Color;
using tracer::Vec3;

tracer::Scene glass_furnace(float ior, tracer::Color absorption = tracer::Color(0.0f)) {
  tracer::Scene scene;
  tracer::Material glass;
  glass.name = "glass";
  glass.type = tracer::MaterialType::Dielectric;
  glass.ior = ior;
  glass.absorption = absorption;
  scene.materials.push_back(glass);
  scene.geometry.spheres.push_back({Vec3(0.0f), 1.0f, 0});
  scene.geometry.finalize();
  scene.background = Color(1.0f);
  scene.camera.position = {0.0f, 0.0f, 4.0f};
  scene.camera.look_at = {0.0f, 0.0f, 0.0f};
  scene.camera.vfov_deg = 32.0f;  // the sphere fills most of the frame
  scene.camera.width = 48;
  scene.camera.height = 48;
  scene.render.max_depth = 64;
  scene.render.min_weight = 1e-7f;
  return scene;
}

tracer::RenderResult render_naive(const tracer::Scene& scene, int threads = 1) {
  const auto boxes = scene.geometry.primitive_bounds();
  const accel::AnyAccel accel = accel::make_accel("naive", nlohmann::json::object(), boxes);
  tracer::RenderOptions options;
  options.threads = threads;
  return tracer::render(scene, accel, options, tracer::whitted_integrator());
}

TEST(WhiteFurnace, ClearGlassSphereConservesEnergy) {
  // Fresnel splitting conserves energy: R + T = 1 at every interface, so a glass sphere in a
  // uniform white background is invisible on average, up to the paths cut off by the limits.
  for (float ior : {1.5f, 1.33f, 2.4f}) {
    const tracer::RenderResult r = render_naive(glass_furnace(ior));
    EXPECT_NEAR(r.image.mean(), 1.0, 1e-3) << "ior " << ior;
    EXPECT_GT(r.rays.refraction, 2000u);  // the sphere was hit and split
    EXPECT_GT(r.rays.reflection, 2000u);
  }
}

TEST(WhiteFurnace, AbsorbingGlassIsDarker) {
  const double clear = render_naive(glass_furnace(1.5f)).image.mean();
  const double tinted = render_naive(glass_furnace(1.5f, Color(0.5f, 0.0f, 0.0f))).image.mean();
  EXPECT_LT(tinted, clear - 0.01);
}

TEST(WhiteFurnace, MatchedIndexSphereIsExactlyInvisible) {
  // ior 1: no reflection, unbent rays: every pixel is exactly the background.
  const tracer::RenderResult r = render_naive(glass_furnace(1.0f));
  for (const auto& p : r.image.pixels()) ASSERT_EQ(p, Color(1.0f));
  EXPECT_EQ(r.rays.reflection, 0u);
}

TEST(Whitted, DiffusePlaneUnderALightMatchesTheRadiometry) {
  // A Lambertian plane of albedo a at distance h below a point light of power P, seen straight
  // down: L = a / pi * P / (4 pi) / h^2.
  tracer::Scene scene;
  tracer::Material m;
  m.name = "matte";
  m.albedo = Color(0.5f);
  scene.materials.push_back(m);
  scene.geometry.planes.push_back({Vec3(0.0f, 1.0f, 0.0f), 0.0f, 0});
  scene.geometry.finalize();
  scene.lights.push_back({Vec3(0.0f, 2.0f, 0.0f), 100.0f, Color(1.0f)});
  scene.camera.position = {0.0f, 1.0f, 0.0f};
  scene.camera.look_at = {0.0f, 0.0f, 0.0f};
  scene.camera.up = {0.0f, 0.0f, 1.0f};
  scene.camera.width = scene.camera.height = 1;
  scene.camera.vfov_deg = 1.0f;
  const tracer::RenderResult r = render_naive(scene);
  const float pi = 3.14159265f;
  EXPECT_NEAR(r.image.at(0, 0).x, 0.5f / pi * 100.0f / (4.0f * pi) / 4.0f, 1e-5f);
  EXPECT_EQ(r.rays.eye, 1u);
  EXPECT_EQ(r.rays.eye_hits, 1u);
  EXPECT_EQ(r.rays.shadow, 1u);
}

TEST(Whitted, ShadowRaysSeeOccluders) {
  tracer::Scene scene;
  tracer::Material m;
  m.name = "matte";
  scene.materials.push_back(m);
  scene.geometry.planes.push_back({Vec3(0.0f, 1.0f, 0.0f), 0.0f, 0});
  scene.geometry.spheres.push_back({Vec3(0.0f, 1.0f, 0.0f), 0.2f, 0});  // between plane and light
  scene.geometry.finalize();
  scene.lights.push_back({Vec3(0.0f, 2.0f, 0.0f), 100.0f, Color(1.0f)});
  scene.camera.position = {0.0f, 0.5f, 0.0f};
  scene.camera.look_at = {0.0f, 0.0f, 0.0f};
  scene.camera.up = {0.0f, 0.0f, 1.0f};
  scene.camera.width = scene.camera.height = 1;
  scene.camera.vfov_deg = 1.0f;
  EXPECT_EQ(render_naive(scene).image.at(0, 0), Color(0.0f));
}

TEST(Whitted, RecursionStopsAtMaxDepthAndMinWeight) {
  // Two parallel mirrors facing each other: the ray bounces until a limit stops it.
  tracer::Scene scene;
  tracer::Material mirror;
  mirror.name = "mirror";
  mirror.type = tracer::MaterialType::Mirror;
  mirror.reflectance = Color(0.5f);
  scene.materials.push_back(mirror);
  scene.geometry.planes.push_back({Vec3(0.0f, 0.0f, 1.0f), -1.0f, 0});
  scene.geometry.planes.push_back({Vec3(0.0f, 0.0f, -1.0f), -1.0f, 0});
  scene.geometry.finalize();
  scene.camera.position = {0.0f, 0.0f, 0.0f};
  scene.camera.look_at = {0.0f, 0.0f, -1.0f};
  scene.camera.width = scene.camera.height = 1;
  scene.camera.vfov_deg = 1.0f;
  scene.render.min_weight = 0.0f;
  scene.render.max_depth = 5;
  EXPECT_EQ(render_naive(scene).rays.reflection, 4u);  // depths 2..5
  scene.render.max_depth = 100;
  scene.render.min_weight = 0.1f;  // 0.5^3 = 0.125 >= 0.1 > 0.5^4
  EXPECT_EQ(render_naive(scene).rays.reflection, 3u);
}

}  // namespace
