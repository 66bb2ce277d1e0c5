#include "tracer/polygon.h"
#include "tracer/triangle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace {

using tracer::Polygon;
using tracer::Ray;
using tracer::Vec3;

/// Polygons over one shared vertex array, as Geometry stores them.
struct Soup {
  std::vector<Vec3> vertices;
  std::vector<Polygon> polygons;

  const Polygon& add(std::vector<Vec3> vs) {
    const auto first = std::uint32_t(vertices.size());
    vertices.insert(vertices.end(), vs.begin(), vs.end());
    polygons.push_back(tracer::make_polygon(vs, first));
    return polygons.back();
  }
  /// Distance along a ray down the z axis from height 1 through (x, y), or +inf.
  float shoot_down(const Polygon& p, float x, float y) const {
    Ray r;
    r.org = Vec3(x, y, 1.0f);
    r.dir = Vec3(0, 0, -1);
    return tracer::intersect_polygon(p, vertices.data(), r);
  }
};

bool hit(float t) { return std::isfinite(t); }

TEST(Polygon, PlaneHitAndBothSides) {
  Soup s;
  const Polygon& sq = s.add({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  EXPECT_EQ(sq.normal, Vec3(0, 0, 1));
  EXPECT_EQ(sq.drop_axis, 2);
  EXPECT_FLOAT_EQ(s.shoot_down(sq, 0.5f, 0.5f), 1.0f);
  Ray up;
  up.org = Vec3(0.5f, 0.5f, -2.0f);
  up.dir = Vec3(0, 0, 1);
  EXPECT_FLOAT_EQ(tracer::intersect_polygon(sq, s.vertices.data(), up), 2.0f);  // back side
  up.tmin = 2.5f;
  EXPECT_FALSE(hit(tracer::intersect_polygon(sq, s.vertices.data(), up)));
  Ray parallel;
  parallel.org = Vec3(-1, 0.5f, 0);
  parallel.dir = Vec3(1, 0, 0);
  EXPECT_FALSE(hit(tracer::intersect_polygon(sq, s.vertices.data(), parallel)));
  EXPECT_FALSE(hit(s.shoot_down(sq, 1.5f, 0.5f)));
}

TEST(Polygon, EdgeRuleIsHalfOpen) {
  Soup s;
  const Polygon sq = s.add({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  // Left and bottom edges are inside, right and top edges outside (see polygon.h).
  EXPECT_TRUE(hit(s.shoot_down(sq, 0.0f, 0.5f)));
  EXPECT_TRUE(hit(s.shoot_down(sq, 0.5f, 0.0f)));
  EXPECT_FALSE(hit(s.shoot_down(sq, 1.0f, 0.5f)));
  EXPECT_FALSE(hit(s.shoot_down(sq, 0.5f, 1.0f)));
  EXPECT_TRUE(hit(s.shoot_down(sq, 0.0f, 0.0f)));
  EXPECT_FALSE(hit(s.shoot_down(sq, 1.0f, 1.0f)));
  EXPECT_FALSE(hit(s.shoot_down(sq, 1.0f, 0.0f)));
  EXPECT_FALSE(hit(s.shoot_down(sq, 0.0f, 1.0f)));
}

TEST(Polygon, SharedEdgeBelongsToExactlyOne) {
  Soup s;
  // Two quads sharing the slanted edge (1, 0)-(1.5, 1), listed in opposite directions.
  const Polygon a = s.add({{0, 0, 0}, {1, 0, 0}, {1.5f, 1, 0}, {0, 1, 0}});
  const Polygon b = s.add({{2, 1, 0}, {1.5f, 1, 0}, {1, 0, 0}, {2, 0, 0}});
  for (int i = 0; i < 16; ++i) {
    const float y = float(i) / 16.0f;
    const float x = 1.0f + 0.5f * y;  // exactly on the shared edge (dyadic values)
    EXPECT_NE(hit(s.shoot_down(a, x, y)), hit(s.shoot_down(b, x, y))) << "y = " << y;
  }
}

TEST(Polygon, ConcaveUsesEvenOdd) {
  Soup s;
  // An L shape: the notch (2, 2) is outside although it lies in the bounding box.
  const Polygon l = s.add({{0, 0, 0}, {3, 0, 0}, {3, 1, 0}, {1, 1, 0}, {1, 3, 0}, {0, 3, 0}});
  EXPECT_TRUE(hit(s.shoot_down(l, 0.5f, 2.5f)));
  EXPECT_TRUE(hit(s.shoot_down(l, 2.5f, 0.5f)));
  EXPECT_FALSE(hit(s.shoot_down(l, 2.0f, 2.0f)));
  // A self-intersecting pentagram: the centre is covered twice, so even-odd says outside,
  // while each point is inside.
  std::vector<Vec3> star;
  for (int i = 0; i < 5; ++i) {
    const float a = 1.5707963f + float(2 * i) * 2.0f * 3.14159265f / 5.0f;
    star.push_back(Vec3(std::cos(a), std::sin(a), 0.0f));
  }
  const Polygon p = s.add(star);
  EXPECT_FALSE(hit(s.shoot_down(p, 0.0f, 0.0f)));
  EXPECT_TRUE(hit(s.shoot_down(p, 0.0f, 0.8f)));
}

TEST(Polygon, MatchesTriangleAwayFromEdges) {
  // Tilted, so the projection drops x (the normal's largest component).
  Soup s;
  const Vec3 p0(1, 0, 0), p1(0.8f, 1, 0.2f), p2(0.7f, 0.3f, 1);
  const Polygon tri = s.add({p0, p1, p2});
  EXPECT_EQ(tri.drop_axis, 0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-0.5f, 1.5f);
  int agree = 0, checked = 0;
  for (int i = 0; i < 5000; ++i) {
    Ray r;
    r.org = Vec3(5.0f, u(rng), u(rng));
    r.dir = Vec3(-1.0f, 0.1f * u(rng), 0.1f * u(rng));
    float bu = 0, bv = 0;
    const float tt = tracer::watertight_distance<float>(p0, p1, p2, r, &bu, &bv);
    const float tp = tracer::intersect_polygon(tri, s.vertices.data(), r);
    if (hit(tt) && std::min({bu, bv, 1.0f - bu - bv}) < 1e-3f) continue;  // too near an edge
    ++checked;
    if (hit(tt) == hit(tp)) ++agree;
    if (hit(tt) && hit(tp)) {
      EXPECT_NEAR(tt, tp, 1e-4f * tt);
    }
  }
  EXPECT_GT(checked, 4000);
  EXPECT_EQ(agree, checked);
}

TEST(Polygon, DegenerateIsNeverHit) {
  Soup s;
  const Polygon line = s.add({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}});
  EXPECT_EQ(line.normal, Vec3(0.0f));
  EXPECT_FALSE(hit(s.shoot_down(line, 1.0f, 0.0f)));
}

TEST(Polygon, BoundsCoverEveryVertex) {
  Soup s;
  const Polygon l = s.add({{0, 0, 0}, {3, 0, 0}, {3, 1, 0.5f}, {1, 1, 0.5f}, {1, 3, 1.5f}, {0, 3, 1.5f}});
  const accel::Aabb b = bounds(l, s.vertices.data());
  EXPECT_EQ(b.lo, Vec3(0, 0, 0));
  EXPECT_EQ(b.hi, Vec3(3, 3, 1.5f));
}

}  // namespace
