// Secondary rays leaving a surface (tracer/offset_ray.h): no acne at any distance from the
// origin, and nothing jumped over. A mirror at |p| = 1e5 must show no acne, so no reflected or
// shadow ray may find its own surface again near t = 0; and the offset must stay near the
// ulp, so that a shadow ray from a floor at 1e5 still meets the sphere resting on it and a
// mirror still reflects its neighbour.

#include "tracer/image_compare.h"
#include "tracer/intersector.h"
#include "tracer/offset_ray.h"
#include "tracer/optics.h"
#include "tracer/render.h"
#include "tracer/scene_transform.h"
#include "tracer/surface.h"

#include "accel/accel.h"
#include "accel/naive.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace {

using tracer::Color;
using tracer::Hit;
using tracer::Ray;
using tracer::SurfacePoint;
using tracer::Vec3;

using Isect = tracer::Intersector<tracer::KindSet::Mixed, false, accel::Naive>;

/// One primitive of each kind around the point `centre`, all facing the world origin.
tracer::Geometry far_mirrors(const Vec3& centre) {
  tracer::Geometry g;
  g.spheres.push_back({centre + Vec3(0.0f, 30.0f, 0.0f), 10.0f, 0});
  const Vec3 tri_c = centre + Vec3(0.0f, -30.0f, 0.0f);
  g.triangles.push_back({tri_c + Vec3(0.0f, -15.0f, -15.0f), tri_c + Vec3(0.0f, 15.0f, -15.0f),
                         tri_c + Vec3(0.0f, 0.0f, 20.0f), 0, -1});
  g.boxes.push_back({centre + Vec3(-5.0f, -5.0f, 25.0f), centre + Vec3(5.0f, 5.0f, 40.0f), 0});
  g.planes.push_back({Vec3(-1.0f, 0.0f, 0.0f), -centre.x - 60.0f, 0});  // x = centre.x + 60
  g.finalize();
  return g;
}

struct AcneCount {
  int hits = 0;       ///< Surface points examined.
  int reflected = 0;  ///< Reflected rays that found their own primitive again.
  int shadow = 0;     ///< Shadow rays towards a light in front blocked by their own primitive.
};

/// Shoots rays from the origin at the far primitives; at every hit spawns a reflected ray and a
/// shadow ray towards a light beside the eye, from `origin_of(sp, side)`.
template <class OriginFn>
AcneCount count_acne(const Vec3& centre, OriginFn&& origin_of) {
  const tracer::Geometry g = far_mirrors(centre);
  const auto boxes = g.primitive_bounds();
  const accel::Naive naive(boxes);
  const Isect isect(g, naive, tracer::TriangleTest::Watertight);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-45.0f, 45.0f);
  AcneCount count;
  const Vec3 light(0.0f, 1000.0f, 0.0f);
  for (int i = 0; i < 4000; ++i) {
    Ray ray;
    ray.dir = glm::normalize(centre + Vec3(0.0f, u(rng), u(rng) * 0.5f + 10.0f) - ray.org);
    const Hit hit = isect.closest(ray);
    if (!hit.found()) continue;
    ++count.hits;
    const SurfacePoint sp = tracer::surface_point(g, ray, hit, tracer::TriangleTest::Watertight);
    const Vec3 n = glm::dot(ray.dir, sp.n_geo) < 0.0f ? sp.n_geo : -sp.n_geo;
    Ray refl;
    refl.org = origin_of(sp, n);
    refl.dir = tracer::reflect(ray.dir, n);
    const Hit again = isect.closest(refl);
    if (again.found() && again.prim == hit.prim) ++count.reflected;
    // Only lights on the lit side are asked for; a shadow by another primitive is no acne.
    const Ray shadow = tracer::segment_to(origin_of(sp, n), light);
    if (glm::dot(shadow.dir, n) > 0.0f) {
      const Hit blocker = isect.closest(shadow);
      if (blocker.found() && blocker.prim == hit.prim) ++count.shadow;
    }
  }
  return count;
}

class FarMirror : public ::testing::TestWithParam<float> {};

TEST_P(FarMirror, OffsetOriginsNeverRehitTheirSurface) {
  const Vec3 centre(GetParam(), 0.0f, 0.0f);
  const AcneCount c = count_acne(
      centre, [](const SurfacePoint& sp, const Vec3& side) { return tracer::offset_ray_origin(sp, side); });
  EXPECT_GT(c.hits, 3000);
  EXPECT_EQ(c.reflected, 0);
  EXPECT_EQ(c.shadow, 0);
}

INSTANTIATE_TEST_SUITE_P(Distances, FarMirror, ::testing::Values(1.0f, 1e3f, 1e5f, 1e6f));

TEST(FarMirror, AFixedEpsilonFailsThere) {
  // The check above can fail: a fixed 1e-4 offset is below one ulp (0.0078) at 1e5.
  const AcneCount c = count_acne(Vec3(1e5f, 0.0f, 0.0f),
                                 [](const SurfacePoint& sp, const Vec3& n) { return sp.p + 1e-4f * n; });
  EXPECT_GT(c.reflected + c.shadow, 100);
}

TEST(OffsetRay, MovesJustPastTheBoundAlongTheNormal) {
  const Vec3 n = glm::normalize(Vec3(1.0f, -1.0f, 0.5f));
  for (const Vec3& p : {Vec3(1e5f, -1e5f, 3e4f), Vec3(-2.0f, 3.0f, -7.0f),
                        Vec3(0.01f, -0.02f, 0.0f), Vec3(-0.0f, 0.0f, 1e-30f), Vec3(7.0f, 0.5f, 1e6f)}) {
    SurfacePoint sp;
    sp.p = p;
    sp.p_error = 3e-7f * glm::abs(p);  // a few ulps of each coordinate
    sp.n_geo = n;
    const double bound = double(glm::dot(glm::abs(n), sp.p_error));
    for (const float side : {1.0f, -1.0f}) {
      const Vec3 o = tracer::offset_ray_origin(sp, side * n);
      double along = 0.0, reach = 0.0;
      for (int a = 0; a < 3; ++a) {
        const double step = double(side * n[a] > 0.0f ? 1.0f : -1.0f) * (double(o[a]) - double(p[a]));
        // No coordinate moves to the wrong side.
        EXPECT_GE(step, 0.0) << a;
        along += double(side) * double(n[a]) * (double(o[a]) - double(p[a]));
        reach = std::max(reach, std::abs(double(n[a])) *
                                    double(std::nextafter(std::abs(o[a]), 1e38f) - std::abs(o[a])));
      }
      // Past the bound along the normal (measured exactly), by at most two steps of the
      // coordinate that reaches furthest plus the rounding of p + bound n.
      EXPECT_GT(along, bound);
      EXPECT_LE(along, bound + 3.0 * reach) << "p " << p.x << " " << p.y << " " << p.z;
    }
  }
}

TEST(OffsetRay, ShadowRayStopsShortOfTheLightsOwnSurface) {
  // A light lying exactly on a ceiling: the shadow ray must not be blocked by that ceiling.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-50.0f, 50.0f);
  for (const float far : {0.0f, 1e3f, 1e5f}) {
    const tracer::Plane ceiling{Vec3(0.0f, -1.0f, 0.0f), -(far + 10.0f), 0};  // y = far + 10
    const Vec3 light(far + 3.0f, far + 10.0f, -7.0f);
    int blocked = 0;
    for (int i = 0; i < 2000; ++i) {
      const Vec3 from(far + u(rng), far + 0.5f * u(rng), u(rng));
      const Ray shadow = tracer::segment_to(from, light);
      EXPECT_LT(shadow.tmax, 1.0f);
      EXPECT_GT(shadow.tmax, 0.999f);
      blocked += tracer::intersect(ceiling, shadow) < shadow.tmax;
    }
    EXPECT_EQ(blocked, 0) << far;
  }
}

/// A diffuse sphere resting on a floor beside a mirror sphere, one light above and to the side:
/// the contact shadow and the mirror's image of its neighbour are what a large offset loses.
tracer::Scene contact_scene() {
  tracer::Scene scene;
  tracer::Material floor_m, ball, mirror;
  floor_m.name = "floor";
  floor_m.albedo = Color(0.7f);
  ball.name = "ball";
  ball.albedo = Color(0.8f, 0.3f, 0.2f);
  mirror.name = "mirror";
  mirror.type = tracer::MaterialType::Mirror;
  scene.materials = {floor_m, ball, mirror};
  scene.geometry.planes.push_back({Vec3(0.0f, 1.0f, 0.0f), 0.0f, 0});
  scene.geometry.spheres.push_back({Vec3(-0.6f, 0.5f, 0.0f), 0.5f, 1});
  scene.geometry.spheres.push_back({Vec3(0.45f, 0.4f, 0.1f), 0.4f, 2});  // 0.05 from the ball
  scene.geometry.finalize();
  scene.lights.push_back({Vec3(-2.0f, 4.0f, 2.0f), 800.0f, Color(1.0f)});
  scene.background = Color(0.2f, 0.3f, 0.5f);
  scene.camera.position = {1.6f, 0.8f, 2.4f};  // facing the mirror's side that sees the ball
  scene.camera.look_at = {0.0f, 0.35f, 0.0f};
  scene.camera.vfov_deg = 40.0f;
  scene.camera.width = 96;
  scene.camera.height = 72;
  return scene;
}

tracer::RenderResult render_naive(const tracer::Scene& scene) {
  const auto boxes = scene.geometry.primitive_bounds();
  tracer::RenderOptions options;
  options.threads = 2;
  return tracer::render(scene, accel::make_accel("naive", {}, boxes), options,
                        tracer::whitted_integrator());
}

TEST(OffsetRay, ContactShadowAndMirrorNeighbourSurviveAt1e5) {
  const tracer::Scene base = contact_scene();
  const tracer::RenderResult ref = render_naive(base);
  // The floor just beside the contact point, in the ball's shadow (towards +x, away from the
  // light), is dark in the reference; the mirror shows the red ball.
  tracer::Scene far = base;
  tracer::translate_scene(far, {1e5, -1e5, 1e5});
  const tracer::RenderResult moved = render_naive(far);
  EXPECT_NEAR(double(moved.rays.shadow), double(ref.rays.shadow), 0.02 * double(ref.rays.shadow));
  EXPECT_NEAR(double(moved.rays.reflection), double(ref.rays.reflection),
              0.02 * double(ref.rays.reflection));

  // Count dark floor pixels (shadow) and red pixels seen in the mirror; both must survive.
  const auto tally = [](const tracer::Image& im) {
    int dark = 0, red = 0;
    for (int y = 0; y < im.height(); ++y)
      for (int x = 0; x < im.width(); ++x) {
        const Color c = im.at(x, y);
        if (std::max({c.r, c.g, c.b}) < 0.02f) ++dark;
        if (x > im.width() / 3 && c.r > 2.0f * c.g && c.r > 0.05f) ++red;
      }
    return std::pair{dark, red};
  };
  const auto [dark_ref, red_ref] = tally(ref.image);
  const auto [dark_far, red_far] = tally(moved.image);
  EXPECT_GT(dark_ref, 50);
  EXPECT_GT(red_ref, 20);
  EXPECT_NEAR(dark_far, dark_ref, 0.05 * dark_ref);
  EXPECT_NEAR(red_far, red_ref, 0.05 * red_ref);
}

}  // namespace
