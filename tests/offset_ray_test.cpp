// Secondary ray origins far from the world origin: a mirror at |p| = 1e5 must show no acne, so
// no reflected or shadow ray may find its own surface again near t = 0.

#include "tracer/intersector.h"
#include "tracer/offset_ray.h"
#include "tracer/optics.h"
#include "tracer/surface.h"

#include "accel/naive.h"

#include <gtest/gtest.h>

#include <random>

namespace {

using tracer::Hit;
using tracer::Ray;
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
/// shadow ray towards a light beside the eye, from `origin_of(p, n)`.
template <class OriginFn>
AcneCount count_acne(const Vec3& centre, OriginFn&& origin_of) {
  const tracer::Geometry g = far_mirrors(centre);
  const auto boxes = g.primitive_bounds();
  const accel::Naive naive(boxes);
  const Isect isect(g, naive);
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
    const tracer::SurfacePoint sp = tracer::surface_point(g, ray, hit);
    const Vec3 n = glm::dot(ray.dir, sp.n_geo) < 0.0f ? sp.n_geo : -sp.n_geo;
    Ray refl;
    refl.org = origin_of(sp.p, n);
    refl.dir = tracer::reflect(ray.dir, n);
    const Hit again = isect.closest(refl);
    if (again.found() && again.prim == hit.prim) ++count.reflected;
    Ray shadow;
    shadow.org = origin_of(sp.p, n);
    shadow.dir = light - shadow.org;
    shadow.tmax = 1.0f;
    // Only lights on the lit side are asked for; a shadow by another primitive is no acne.
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
  const AcneCount c = count_acne(centre, tracer::offset_ray_origin);
  EXPECT_GT(c.hits, 3000);
  EXPECT_EQ(c.reflected, 0);
  EXPECT_EQ(c.shadow, 0);
}

INSTANTIATE_TEST_SUITE_P(Distances, FarMirror, ::testing::Values(1.0f, 1e3f, 1e5f));

TEST(FarMirror, AFixedEpsilonFailsThere) {
  // The check above can fail: a fixed 1e-4 offset is below one ulp (0.0078) at 1e5.
  const AcneCount c = count_acne(Vec3(1e5f, 0.0f, 0.0f),
                                 [](const Vec3& p, const Vec3& n) { return p + 1e-4f * n; });
  EXPECT_GT(c.reflected + c.shadow, 100);
}

TEST(OffsetRay, MovesToTheNormalsSideByUlpsFarAndByAConstantNearTheOrigin) {
  const Vec3 n = glm::normalize(Vec3(1.0f, -1.0f, 0.5f));
  for (const Vec3& p : {Vec3(1e5f, -1e5f, 3e4f), Vec3(-2.0f, 3.0f, -7.0f),
                        Vec3(0.01f, -0.02f, 0.0f), Vec3(-0.0f, 0.0f, 1e-30f)}) {
    const Vec3 o = tracer::offset_ray_origin(p, n);
    for (int a = 0; a < 3; ++a) {
      if (n[a] > 0.0f) {
        EXPECT_GT(o[a], p[a]) << a;
      } else if (n[a] < 0.0f) {
        EXPECT_LT(o[a], p[a]) << a;
      }
    }
    EXPECT_GT(glm::dot(o - p, n), 0.0f);
    // Small: a few hundred ulps of the largest coordinate, or 1/65536 near the origin.
    const float scale = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z), 1.0f / 32.0f});
    EXPECT_LT(glm::length(o - p), 512.0f * scale * 1.2e-7f + 1e-4f);
  }
}

}  // namespace
