#pragma once
// Test support for the octree and kd-tree suites: seeded sphere scenes, adversarial rays (exact
// +-0 direction components, rays lying in the tree's own split planes and on primitive box
// faces, origins inside and outside, varied [tmin, tmax]), and the check that a structure gives
// the naive loop's answer to every ray: the same primitive, a bit-equal t, the same any-hit.

#include "accel/accel.h"
#include "tracer/scene_geometry.h"
#include "tracer/intersector.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <random>
#include <span>
#include <string>
#include <vector>

namespace sphere_oracle {

using accel::Aabb;
using accel::Ray;
using accel::Vec3;

enum class SceneKind { Uniform, HugeAmongTiny, Line, Duplicates, Grid, Single, Empty };

inline const char* scene_name(SceneKind k) {
  static const char* names[] = {"uniform", "huge_among_tiny", "line", "duplicates",
                               "grid",    "single",          "empty"};
  return names[int(k)];
}

inline tracer::Geometry make_scene(SceneKind kind, std::uint32_t seed) {
  tracer::Geometry g;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-4.0f, 4.0f), radius(0.05f, 0.6f);
  auto add = [&g](Vec3 c, float r) { g.spheres.push_back({c, r, 0}); };
  switch (kind) {
    case SceneKind::Uniform:
      for (int i = 0; i < 150; ++i) add({u(rng), u(rng), u(rng)}, radius(rng));
      break;
    case SceneKind::HugeAmongTiny:
      for (int i = 0; i < 100; ++i) add({u(rng), u(rng), u(rng)}, 0.02f);
      add({0.3f, -0.2f, 0.1f}, 30.0f);
      std::shuffle(g.spheres.begin(), g.spheres.end(), rng);
      break;
    case SceneKind::Line:
      for (int i = 0; i < 60; ++i) add({0.0f, 1.0f, -3.0f + 0.1f * float(i)}, 0.25f);
      break;
    case SceneKind::Duplicates:
      for (int i = 0; i < 25; ++i) {
        const Vec3 c(u(rng), u(rng), u(rng));
        const float r = radius(rng);
        for (int k = 0; k < 3; ++k) add(c, r);
      }
      std::shuffle(g.spheres.begin(), g.spheres.end(), rng);
      break;
    case SceneKind::Grid:  // touching spheres whose box faces lie on the midpoint planes
      for (int x = 0; x < 6; ++x)
        for (int y = 0; y < 6; ++y)
          for (int z = 0; z < 4; ++z) add({float(x), float(y), float(z)}, 0.5f);
      break;
    case SceneKind::Single:
      add({0.5f, -0.25f, 1.0f}, 0.75f);
      break;
    case SceneKind::Empty:
      break;
  }
  g.finalize();
  return g;
}

/// A plane a tree splits on: coordinate `pos` on `axis`.
struct AxisPlane {
  int axis;
  float pos;
};

inline std::vector<Ray> make_rays(const tracer::Geometry& g, std::span<const AxisPlane> planes,
                                  std::uint32_t seed) {
  const std::vector<Aabb> boxes = g.primitive_bounds();
  Aabb box;
  for (const Aabb& b : boxes) box.grow(b);
  if (box.is_empty()) box = {Vec3(-1.0f), Vec3(1.0f)};
  const Vec3 c = box.center();
  const float size = glm::length(box.extent()) + 1.0f;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f), u11(-1.0f, 1.0f);
  auto in_box = [&] { return box.lo + Vec3(u01(rng), u01(rng), u01(rng)) * box.extent(); };
  auto dir = [&] {
    Vec3 d;
    do d = Vec3(u11(rng), u11(rng), u11(rng));
    while (glm::dot(d, d) < 1e-3f);
    return d;
  };
  auto zero = [&] { return (rng() & 1) ? 0.0f : -0.0f; };
  std::vector<Ray> rays;
  auto add = [&rays](Vec3 o, Vec3 d) { rays.push_back(Ray{o, 0.0f, d, accel::kInfinity}); };

  for (int i = 0; i < 60; ++i) {  // from outside into the scene
    const Vec3 o = c + size * glm::normalize(dir());
    add(o, in_box() - o);
  }
  for (int i = 0; i < 60; ++i) add(in_box(), dir());  // from inside
  for (int i = 0; i < 60; ++i) {  // one or two exact +-0 components
    Vec3 d = dir();
    const int a = int(rng() % 3);
    d[a] = zero();
    if (rng() & 1) d[(a + 1) % 3] = zero();
    add(in_box() - size * d, d);
  }
  for (int i = 0; i < 100 && !planes.empty(); ++i) {  // lying in one of the tree's planes
    const AxisPlane p = planes[rng() % planes.size()];
    Vec3 o = in_box(), d = dir();
    o[p.axis] = p.pos;
    d[p.axis] = zero();
    if (rng() & 1) {  // and in a second plane too: along a cell edge
      const AxisPlane q = planes[rng() % planes.size()];
      if (q.axis != p.axis) {
        o[q.axis] = q.pos;
        d[q.axis] = zero();
      }
    }
    add((rng() & 1) ? o : o - size * d, d);
  }
  for (std::size_t i = 0; i < 40 && !boxes.empty(); ++i) {  // on box faces, through centres
    const Aabb& b = boxes[rng() % boxes.size()];
    const int a = int(rng() % 3), along = (a + 1) % 3;
    Vec3 o = b.center(), d(zero(), zero(), zero());
    d[along] = (rng() & 1) ? 1.0f : -1.0f;
    o[along] = c[along] - d[along] * size;
    add(o, d);  // through the centre: the hits lie on the box faces
    o[a] = (rng() & 1) ? b.lo[a] : b.hi[a];
    add(o, d);  // tangent to the sphere
  }
  const std::size_t n = rays.size();
  for (std::size_t i = 0; i < n; i += 2) {  // varied intervals
    Ray r = rays[i];
    r.tmin = (rng() & 1) ? u01(rng) * 0.5f : -u01(rng);
    r.tmax = (rng() & 1) ? accel::kInfinity : r.tmin + u01(rng) * size;
    rays.push_back(r);
  }
  return rays;
}

inline std::string describe(const Ray& r) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "org (%a %a %a) dir (%a %a %a) [%a, %a]", r.org.x, r.org.y,
                r.org.z, r.dir.x, r.dir.y, r.dir.z, r.tmin, r.tmax);
  return buf;
}

/// Traces every ray with `structure` and with naive; reports the first few differences.
template <bool Count = false, class Structure>
::testing::AssertionResult matches_naive(const tracer::Geometry& g, const Structure& structure,
                                         std::span<const Ray> rays) {
  using tracer::KindSet;
  const accel::Naive naive(g.primitive_bounds());
  accel::TraversalCounters counters;
  const tracer::Intersector<KindSet::SpheresOnly, Count, Structure> isect(g, structure, tracer::TriangleTest::Watertight, &counters);
  const tracer::Intersector<KindSet::SpheresOnly, false, accel::Naive> ref(g, naive, tracer::TriangleTest::Watertight);
  int bad = 0;
  std::string what;
  for (const Ray& r : rays) {
    const tracer::Hit h = isect.closest(r), e = ref.closest(r);
    const bool occ = isect.occluded(r), e_occ = ref.occluded(r);
    if (h.prim == e.prim && std::bit_cast<std::uint32_t>(h.t) == std::bit_cast<std::uint32_t>(e.t) &&
        occ == e_occ)
      continue;
    if (++bad <= 3)
      what += "\n  " + describe(r) + ": prim " + std::to_string(h.prim) + " t " +
              std::to_string(h.t) + " occluded " + std::to_string(occ) + "; naive prim " +
              std::to_string(e.prim) + " t " + std::to_string(e.t) + " occluded " +
              std::to_string(e_occ);
  }
  if constexpr (Count) {
    if (counters.rays != 2 * rays.size())
      return ::testing::AssertionFailure() << "counted " << counters.rays << " queries";
  }
  if (bad) return ::testing::AssertionFailure() << bad << " of " << rays.size() << " rays differ" << what;
  return ::testing::AssertionSuccess();
}

}  // namespace sphere_oracle
