// The ray/triangle routines (tracer/triangle.h): watertight agrees with Moller-Trumbore away from
// edges, and a closed mesh never lets a watertight ray out, even when the ray is aimed exactly at
// a shared edge or vertex. Moller-Trumbore's count of escaped rays on the same rays is printed.

#include "scenes_gen/closed_meshes.h"
#include "tracer/intersector.h"
#include "tracer/scene_geometry.h"
#include "tracer/triangle.h"
#include "tracer/triangle_box.h"

#include "accel/accel.h"
#include "accel/bvh.h"
#include "accel/triangle_hit.h"
#include "accel/triangle_soa.h"
#include "accel/wide_bvh/wide_bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>
#include <string>

namespace {

using accel::Ray;
using accel::Vec3;
using tracer::TriangleTest;

constexpr float kInf = accel::kInfinity;

TEST(Triangle, WatertightAgreesWithMollerAwayFromEdges) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int compared = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 p0(u(rng), u(rng), u(rng)), p1(u(rng), u(rng), u(rng)), p2(u(rng), u(rng), u(rng));
    Ray r;
    r.org = Vec3(u(rng), u(rng), u(rng)) * 3.0f;
    r.dir = Vec3(u(rng), u(rng), u(rng));
    float mu = 0, mv = 0, wu = 0, wv = 0;
    const float tm = tracer::moller_distance<float>(p0, p1, p2, r, &mu, &mv);
    const float tw = tracer::watertight_distance<float>(p0, p1, p2, r, &wu, &wv);
    const float edge = std::min({mu, mv, 1.0f - mu - mv});
    if (tm < kInf && edge < 1e-3f) continue;  // near an edge: either may decide
    if (tm < kInf && tm < 1e-3f) continue;    // at the origin: the watertight bound on t decides
    ++compared;
    ASSERT_EQ(tm < kInf, tw < kInf) << "ray " << i;
    if (tm < kInf) {
      EXPECT_NEAR(tw, tm, 1e-4f * tm) << "ray " << i;
      EXPECT_NEAR(wu, mu, 1e-4f) << "ray " << i;
      EXPECT_NEAR(wv, mv, 1e-4f) << "ray " << i;
    }
  }
  EXPECT_GT(compared, 19000);
}

// The bound that keeps a watertight hit only where t is surely positive must scale with the
// scene and with the ray's length: shadow-like segments (the direction is the whole segment,
// t in (0, 1)) through triangles at every scale from 10^-6 to 10^4 are hit wherever Moller-Trumbore
// hits them well inside. (pbrt-v4's bound adds a z measured in t to x and y measured in world
// units: at 10^-4 it dropped every such hit, and the stability suite lost the bunny's shadows.)
TEST(Triangle, WatertightHitsShortSegmentsAtEveryScale) {
  for (const float scale : {1e-6f, 1e-4f, 1.0f, 1e4f}) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), w(0.15f, 0.7f);
    int hits = 0, missed = 0;
    for (int i = 0; i < 5000; ++i) {
      const Vec3 p0 = Vec3(u(rng), u(rng), u(rng)) * scale, p1 = Vec3(u(rng), u(rng), u(rng)) * scale,
                 p2 = Vec3(u(rng), u(rng), u(rng)) * scale;
      const float b1 = w(rng), b2 = w(rng) * (1.0f - b1);
      const Vec3 target = p0 + b1 * (p1 - p0) + b2 * (p2 - p0);  // well inside
      Ray r;
      r.org = target + Vec3(u(rng), u(rng), u(rng)) * (0.3f * scale);
      r.dir = (target - r.org) * (1.0f + 1.0f + u(rng));  // the segment to a point past the triangle
      r.tmax = 1.0f;
      float mu = 0, mv = 0;
      if (tracer::moller_distance<float>(p0, p1, p2, r, &mu, &mv) == kInf) continue;
      if (std::min({mu, mv, 1.0f - mu - mv}) < 0.05f) continue;
      ++hits;
      missed += tracer::watertight_distance<float>(p0, p1, p2, r) == kInf;
    }
    EXPECT_GT(hits, 1000) << "scale " << scale;
    EXPECT_EQ(missed, 0) << "scale " << scale << ": " << missed << " of " << hits << " segments missed";
  }
}

TEST(Triangle, DoubleRoutinesAgreeWithFloatOnes) {
  const glm::dvec3 p0(0, 0, 0), p1(1, 0, 0), p2(0, 1, 0);
  tracer::RayD r;
  r.org = {0.25, 0.25, 2.0};
  r.dir = {0.0, 0.0, -1.0};
  double u = 0, v = 0;
  EXPECT_DOUBLE_EQ(tracer::watertight_distance<double>(p0, p1, p2, r, &u, &v), 2.0);
  EXPECT_DOUBLE_EQ(u, 0.25);
  EXPECT_DOUBLE_EQ(v, 0.25);
  EXPECT_DOUBLE_EQ(tracer::moller_distance<double>(p0, p1, p2, r), 2.0);
}

TEST(Triangle, DegenerateAndParallelAreNeverHit) {
  Ray r;
  r.org = Vec3(0.2f, 0.2f, 1.0f);
  r.dir = Vec3(0.0f, 0.0f, -1.0f);
  for (const TriangleTest t : {TriangleTest::Watertight, TriangleTest::Moller}) {
    // Collinear vertices, a repeated vertex, and a triangle containing the ray.
    EXPECT_EQ(tracer::triangle_distance<float>(t, Vec3(0), Vec3(1, 1, 0), Vec3(2, 2, 0), r), kInf);
    EXPECT_EQ(tracer::triangle_distance<float>(t, Vec3(0), Vec3(0), Vec3(1, 0, 0), r), kInf);
    EXPECT_EQ(tracer::triangle_distance<float>(t, Vec3(0.2f, 0.2f, 0), Vec3(0.2f, 0.2f, 2), Vec3(1, 0, 0), r), kInf);
  }
}

// The structures' SIMD triangle leaves run the scalar routines lane by lane
// (accel/triangle_hit.h): each lane must give the scalar t to the bit, on random triangles at
// every scale, on rays aimed exactly at vertices and edges (edge functions of exactly 0, which
// both take again in double), on degenerate triangles and on rays along an axis.
TEST(Triangle, SimdLanesEqualTheScalarRoutinesBitForBit) {
  using Batch = accel::simd::FloatLeaf;
  constexpr std::size_t n = Batch::size;
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), s01(0.0f, 1.0f);
  std::uniform_int_distribution<int> kind(0, 5);
  std::uint64_t lanes = 0, hits[2] = {0, 0};
  for (const float scale : {1e-5f, 1.0f, 3e4f}) {
    for (int batch = 0; batch < 20000; ++batch) {
      alignas(64) float coords[3][3][n];
      Vec3 p[n][3];
      for (std::size_t i = 0; i < n; ++i) {
        for (int v = 0; v < 3; ++v) p[i][v] = Vec3(u(rng), u(rng), u(rng)) * scale;
        if (i == 3) p[i][2] = p[i][1];                           // a repeated vertex
        if (i == 5) p[i][2] = p[i][0] + 2.0f * (p[i][1] - p[i][0]);  // nearly collinear
        if (i > 0 && i % 2 == 0) p[i][0] = p[i - 1][1], p[i][1] = p[i - 1][0];  // shares an edge
        for (int v = 0; v < 3; ++v)
          for (int a = 0; a < 3; ++a) coords[v][a][i] = p[i][v][a];
      }
      accel::TriangleLanes<Batch> tri;
      for (int v = 0; v < 3; ++v)
        for (int a = 0; a < 3; ++a) tri.p[v][a] = Batch::load_aligned(coords[v][a]);
      Ray r;
      r.org = Vec3(u(rng), u(rng), u(rng)) * (3.0f * scale);
      const Vec3* target = p[std::size_t(batch) % n];
      switch (kind(rng)) {
        case 0: r.dir = target[0] - r.org; break;                                          // at a vertex
        case 1: r.dir = target[0] + s01(rng) * (target[1] - target[0]) - r.org; break;    // at an edge
        case 2: r.dir = Vec3(0.0f, 0.0f, u(rng) < 0.0f ? -1.0f : 1.0f); break;           // along an axis
        case 3: r.dir = Vec3(u(rng), 0.0f, u(rng)); break;                                // a zero component
        default: r.dir = Vec3(u(rng), u(rng), u(rng)) * scale; break;
      }
      r.tmin = (batch % 7 == 0) ? 0.5f : 0.0f;
      alignas(64) float got[2][n];
      accel::watertight_lanes(tri, r, accel::WatertightRay(r)).store_aligned(got[0]);
      accel::moller_lanes(tri, r).store_aligned(got[1]);
      for (std::size_t i = 0; i < n; ++i) {
        const float want[2] = {tracer::watertight_distance<float>(p[i][0], p[i][1], p[i][2], r),
                               tracer::moller_distance<float>(p[i][0], p[i][1], p[i][2], r)};
        for (int k = 0; k < 2; ++k) {
          ASSERT_EQ(std::bit_cast<std::uint32_t>(got[k][i]), std::bit_cast<std::uint32_t>(want[k]))
              << (k == 0 ? "watertight" : "moller") << " lane " << i << " of batch " << batch << " at scale "
              << scale << ": " << got[k][i] << " for " << want[k];
          hits[k] += want[k] < kInf;
        }
        ++lanes;
      }
    }
  }
  // Enough hits that the comparison is not of misses only.
  EXPECT_GT(hits[0], lanes / 40);
  EXPECT_GT(hits[1], lanes / 40);
}

// WatertightRay picks its axes without branches; the scalar routine with nested conditionals.
// Every direction made of ties, signed zeros, infinities and NaN gets the scalar routine's axes
// and shear, and the lanes give the scalar routine's t bit for bit.
TEST(Triangle, TheRaysAxesAreTheScalarRoutinesOnTiesZerosAndNaN) {
  using Batch = accel::simd::FloatLeaf;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float values[] = {0.0f, -0.0f, 1.0f, -1.0f, 2.0f, -2.0f, 1e-30f, kInf, -kInf, nan};
  const Vec3 p0(-1.0f, -1.5f, 3.0f), p1(2.0f, -1.0f, 2.5f), p2(0.5f, 2.0f, -3.0f);
  alignas(64) float rows[3][3][Batch::size];
  for (int v = 0; v < 3; ++v)
    for (int a = 0; a < 3; ++a)
      for (std::size_t i = 0; i < Batch::size; ++i) rows[v][a][i] = (v == 0 ? p0 : v == 1 ? p1 : p2)[a];
  accel::TriangleLanes<Batch> tri;
  for (int v = 0; v < 3; ++v)
    for (int a = 0; a < 3; ++a) tri.p[v][a] = Batch::load_aligned(rows[v][a]);
  int rays = 0, hits = 0;
  for (const float x : values)
    for (const float y : values)
      for (const float z : values) {
        Ray r;
        r.org = Vec3(0.25f, -0.5f, 0.125f);
        r.dir = Vec3(x, y, z);
        const accel::WatertightRay w(r);
        const float ad[3] = {std::abs(x), std::abs(y), std::abs(z)};
        const int kz = ad[0] > ad[1] ? (ad[0] > ad[2] ? 0 : 2) : (ad[1] > ad[2] ? 1 : 2);
        const int kx = kz == 2 ? 0 : kz + 1;
        const int ky = kx == 2 ? 0 : kx + 1;
        SCOPED_TRACE("direction (" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) + ")");
        ASSERT_EQ(w.kz, kz);
        ASSERT_EQ(w.kx, kx);
        ASSERT_EQ(w.ky, ky);
        const float dz = r.dir[kz];
        ASSERT_EQ(w.valid, dz != 0.0f && std::isfinite(dz));
        if (w.valid) {
          ASSERT_EQ(std::bit_cast<std::uint32_t>(w.sx), std::bit_cast<std::uint32_t>(-r.dir[kx] / dz));
          ASSERT_EQ(std::bit_cast<std::uint32_t>(w.sy), std::bit_cast<std::uint32_t>(-r.dir[ky] / dz));
          ASSERT_EQ(std::bit_cast<std::uint32_t>(w.sz), std::bit_cast<std::uint32_t>(1.0f / dz));
        }
        alignas(64) float got[Batch::size];
        accel::watertight_lanes(tri, r, w).store_aligned(got);
        const float want = tracer::watertight_distance<float>(p0, p1, p2, r);
        ASSERT_EQ(std::bit_cast<std::uint32_t>(got[0]), std::bit_cast<std::uint32_t>(want));
        ++rays;
        hits += want < kInf;
      }
  EXPECT_EQ(rays, 1000);
  EXPECT_GT(hits, 0);  // some of these directions hit the triangle, so t itself is compared
}

/// A leaf function for TriangleSoA::test that keeps the nearest accepted hit and runs `test`.
struct NearestLeaf {
  TriangleTest test;
  std::uint32_t id = tracer::Hit::kNone;
  bool accept(std::uint32_t prim, float t, Ray& ray) {
    if (!(t < ray.tmax)) return false;
    ray.tmax = t, id = prim;
    return true;
  }
  TriangleTest triangle_test() const { return test; }
};

TEST(Triangle, LeafRowsGiveEveryLeafItsOwnTrianglesAtAnyCount) {
  // Leaves of 1 to 19 triangles (past two batches of eight), over a shuffled id array, the last
  // leaf ending the rows: every ray aimed at a triangle's centroid gets, from that triangle's
  // leaf, the hit the scalar routine gives on the leaf's triangles, with either routine.
  std::mt19937 rng(31);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<accel::TriangleShape> shapes;
  std::vector<accel::LeafRange> leaves;
  for (std::uint32_t count = 1, first = 0; count <= 19; first += count, ++count) leaves.push_back({first, count});
  const std::uint32_t n = leaves.back().first + leaves.back().count;
  for (std::uint32_t i = 0; i < n; ++i) {
    const Vec3 c(u(rng) * 10.0f, u(rng) * 10.0f, u(rng) * 10.0f);
    shapes.push_back({c + Vec3(u(rng), u(rng), u(rng)), c + Vec3(u(rng), u(rng), u(rng)), c + Vec3(u(rng), u(rng), u(rng))});
  }
  std::vector<std::uint32_t> ids(n);
  for (std::uint32_t i = 0; i < n; ++i) ids[i] = i;
  std::shuffle(ids.begin(), ids.end(), rng);
  accel::TriangleSoA soa;
  soa.build(ids, leaves, shapes);
  std::uint64_t hits = 0;
  for (const TriangleTest test : {TriangleTest::Watertight, TriangleTest::Moller})
    for (const auto& leaf : leaves)
      for (std::uint32_t j = leaf.first; j < leaf.first + leaf.count; ++j) {
        const accel::TriangleShape& target = shapes[ids[j]];
        Ray r;
        r.org = Vec3(u(rng), u(rng), u(rng)) * 30.0f;
        r.dir = (target.p0 + target.p1 + target.p2) / 3.0f - r.org;
        Ray want = r;
        std::uint32_t want_id = tracer::Hit::kNone;
        for (std::uint32_t k = leaf.first; k < leaf.first + leaf.count; ++k) {
          const accel::TriangleShape& t = shapes[ids[k]];
          const float d = test == TriangleTest::Watertight ? tracer::watertight_distance<float>(t.p0, t.p1, t.p2, want)
                                                           : tracer::moller_distance<float>(t.p0, t.p1, t.p2, want);
          if (d < want.tmax) want.tmax = d, want_id = ids[k];
        }
        NearestLeaf got{test};
        Ray ray = r;
        bool hit = false;
        soa.test<false, false>(ids.data(), leaf.first, leaf.count, ray, accel::WatertightRay(ray), got, nullptr, hit);
        ASSERT_EQ(got.id, want_id) << "leaf of " << leaf.count << ", triangle " << j - leaf.first;
        ASSERT_EQ(std::bit_cast<std::uint32_t>(ray.tmax), std::bit_cast<std::uint32_t>(want.tmax));
        hits += want_id != tracer::Hit::kNone;
      }
  // Rays aimed at centroids hit (a few may graze a nearer triangle's edge, which is still a hit).
  EXPECT_GT(hits, 2u * n * 9u / 10u);
}

/// Rays from points inside a closed mesh aimed exactly at its shared vertices and at points on
/// its shared edges; counts those that hit nothing (escaped through the surface).
std::uint64_t escapes(const tracer::MeshData& mesh, float inside, TriangleTest test, std::uint64_t rays,
                      std::uint32_t seed) {
  tracer::Geometry g;
  for (const auto& t : mesh.triangles)
    g.triangles.push_back({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], 0});
  g.finalize();
  accel::AnyAccel bvh = accel::make_accel("bvh8", nullptr, g.primitive_bounds());
  tracer::attach_geometry(bvh, g);  // as a render builds it: SIMD triangle leaves
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-inside, inside), s(0.0f, 1.0f);
  std::uniform_int_distribution<std::size_t> pick(0, mesh.triangles.size() - 1);
  std::uniform_int_distribution<int> corner(0, 2);
  std::uint64_t out = 0;
  tracer::with_intersector<false>(g, bvh, test, [&](const auto& isect) {
    for (std::uint64_t i = 0; i < rays; ++i) {
      const auto& t = mesh.triangles[pick(rng)];
      const int c = corner(rng);
      const Vec3 a = mesh.vertices[t[std::size_t(c)]], b = mesh.vertices[t[std::size_t((c + 1) % 3)]];
      // Half the rays at a vertex, half at a point of an edge (rounded to float: just on one
      // side of the exact edge or the other, which is where a test that decides each triangle
      // alone lets rays through).
      const Vec3 target = (i & 1) ? a : a + s(rng) * (b - a);
      Ray r;
      r.org = Vec3(u(rng), u(rng), u(rng));
      r.dir = target - r.org;
      if (!isect.closest(r).found()) ++out;
    }
  });
  return out;
}

struct ClosedMesh {
  const char* name;
  tracer::MeshData mesh;
  float inside;  ///< Half the side of the cube of ray origins, all inside the mesh.
};

TEST(Triangle, ClosedMeshesNeverLeakWatertightRays) {
  const ClosedMesh meshes[] = {{"icosphere(4)", scenes_gen::icosphere(4), 0.5f},
                               {"grid cube 24x24 per face, seen from inside", scenes_gen::grid_cube(24), 0.9f}};
  constexpr std::uint64_t kRays = 5'000'000;  // per mesh: 10^7 in all
  for (const ClosedMesh& m : meshes) {
    const std::uint64_t watertight = escapes(m.mesh, m.inside, TriangleTest::Watertight, kRays, 11);
    const std::uint64_t moller = escapes(m.mesh, m.inside, TriangleTest::Moller, kRays, 11);
    std::printf("%s: %llu rays at shared edges and vertices: watertight %llu escaped, moller %llu escaped\n", m.name,
                static_cast<unsigned long long>(kRays), static_cast<unsigned long long>(watertight),
                static_cast<unsigned long long>(moller));
    RecordProperty(std::string(m.name) + " moller escaped", std::to_string(moller));
    EXPECT_EQ(watertight, 0u) << m.name;
  }
}

TEST(Triangle, ClosedMeshesAreClosedAndOutward) {
  for (const tracer::MeshData& m : {scenes_gen::icosphere(3), scenes_gen::grid_cube(5)}) {
    // Every edge is shared by exactly two triangles, in opposite directions.
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    for (const auto& t : m.triangles)
      for (int k = 0; k < 3; ++k) ++edges[{t[std::size_t(k)], t[std::size_t((k + 1) % 3)]}];
    for (const auto& [e, n] : edges) {
      EXPECT_EQ(n, 1);
      EXPECT_EQ(edges.count({e.second, e.first}), 1u);
    }
    for (const auto& t : m.triangles) {
      const glm::dvec3 a(m.vertices[t[0]]), b(m.vertices[t[1]]), c(m.vertices[t[2]]);
      EXPECT_GT(glm::dot(glm::cross(b - a, c - a), a + b + c), 0.0) << "a triangle faces inward";
    }
  }
  EXPECT_EQ(scenes_gen::icosphere(3).triangles.size(), scenes_gen::icosphere_triangles(3));
}

TEST(TriangleBox, TheSeparatingAxisTestDecidesWhereBoxesCannot) {
  const accel::Aabb unit{Vec3(0.0f), Vec3(1.0f)};
  const auto tri = [](Vec3 a, Vec3 b, Vec3 c) { return tracer::Triangle{a, b, c, 0, -1}; };
  // Inside, crossing a face, and touching a face exactly.
  EXPECT_TRUE(tracer::triangle_touches_box(tri({0.2f, 0.2f, 0.5f}, {0.8f, 0.2f, 0.5f}, {0.5f, 0.8f, 0.5f}), unit, 0.0));
  EXPECT_TRUE(tracer::triangle_touches_box(tri({-1, 0.5f, 0.5f}, {2, 0.5f, 0.5f}, {0.5f, 2, 0.5f}), unit, 0.0));
  EXPECT_TRUE(tracer::triangle_touches_box(tri({1, 0, 0}, {1, 1, 0}, {1, 0, 1}), unit, 0.0));
  // A triangle passing the corner (1, 1, 1), x + y + z = 3.5, whose box covers the cell: its
  // plane separates.
  const tracer::Triangle corner = tri({3.5f, 0.0f, 0.0f}, {0.0f, 3.5f, 0.0f}, {0.0f, 0.0f, 3.5f});
  EXPECT_FALSE(tracer::triangle_touches_box(corner, unit, 0.0));
  EXPECT_TRUE(tracer::triangle_touches_box(corner, unit, 0.5));  // the margin widens the box
  // A long thin sliver along the diagonal of the xy-plane at z = 0.5, beside the box: only an
  // edge-by-axis product separates it.
  EXPECT_FALSE(tracer::triangle_touches_box(tri({1.3f, -0.2f, 0.5f}, {3.0f, 1.5f, 0.5f}, {3.0f, 1.49f, 0.5f}), unit, 0.0));
}

/// `n` long thin triangles in random directions, `half_length` each way from a point in a 10-unit
/// cube: their boxes span much of the scene, the triangles cross few cells.
tracer::Geometry long_diagonal_triangles(int n, float half_length) {
  tracer::Geometry g;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f);
  for (int i = 0; i < n; ++i) {
    const Vec3 a(u(rng), u(rng), u(rng)), d = glm::normalize(Vec3(u(rng), u(rng), u(rng))) * half_length;
    g.triangles.push_back({a - d, a + d, a + d + Vec3(0.01f, 0.02f, 0.0f), 0});
  }
  g.finalize();
  return g;
}

TEST(TriangleBox, TreesThatDivideSpaceKeepOnlyTheCellsATriangleTouches) {
  const tracer::Geometry g = long_diagonal_triangles(400, 8.0f);
  const auto boxes = g.primitive_bounds();
  for (const char* name : {"octree", "kdtree"}) {
    accel::BuildLimits with;
    with.overlap = tracer::primitive_overlap(g);
    const nlohmann::json knobs = {{"max_depth", 5}, {"max_leaf_size", 4}};
    const std::uint64_t by_box = accel::stats_of(accel::make_accel(name, knobs, boxes)).prim_refs;
    const std::uint64_t by_triangle = accel::stats_of(accel::make_accel(name, knobs, boxes, with)).prim_refs;
    std::printf("%s: %llu references by box, %llu by the triangle test\n", name,
                static_cast<unsigned long long>(by_box), static_cast<unsigned long long>(by_triangle));
    EXPECT_LT(double(by_triangle), 0.6 * double(by_box)) << name;
  }
}

TEST(TriangleBox, TheClippedPartHoldsEveryPointOfTheTriangleInTheCell) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  std::uniform_real_distribution<double> w(0.0, 1.0);
  const accel::Aabb cell{Vec3(-0.5f, -0.25f, -1.0f), Vec3(0.75f, 0.5f, 0.25f)};
  const double margin = 1e-4;
  int clipped = 0, tighter = 0;
  for (int n = 0; n < 2000; ++n) {
    const tracer::Triangle t{Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng)), 0, -1};
    accel::Aabb part;
    const bool some = tracer::clip_triangle_to_box(t, cell, margin, part);
    // Every sampled point of the triangle inside the cell lies in the part; with no part, none
    // lies in the cell.
    int inside = 0;
    for (int k = 0; k < 400; ++k) {
      double a = w(rng), b = w(rng);
      if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
      const glm::dvec3 p = glm::dvec3(t.p0) + a * (glm::dvec3(t.p1) - glm::dvec3(t.p0)) +
                           b * (glm::dvec3(t.p2) - glm::dvec3(t.p0));
      if (glm::any(glm::lessThan(p, glm::dvec3(cell.lo))) || glm::any(glm::greaterThan(p, glm::dvec3(cell.hi)))) continue;
      ++inside;
      ASSERT_TRUE(some) << "triangle " << n << " has a point in the cell but no part";
      ASSERT_TRUE(glm::all(glm::greaterThanEqual(p, glm::dvec3(part.lo))) && glm::all(glm::lessThanEqual(p, glm::dvec3(part.hi))))
          << "triangle " << n << ", sample " << k;
    }
    if (!some) {
      EXPECT_EQ(inside, 0);
      EXPECT_FALSE(tracer::triangle_touches_box(t, cell, 0.0)) << "triangle " << n;
      continue;
    }
    ++clipped;
    // The part never exceeds the triangle's box widened by the margin, and is often smaller
    // than the box's part in the cell.
    accel::Aabb box = accel::Aabb::of_point(t.p0);
    box.grow(t.p1);
    box.grow(t.p2);
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(part.lo[a], box.lo[a] - 2.0 * margin);
      EXPECT_LE(part.hi[a], box.hi[a] + 2.0 * margin);
    }
    const Vec3 by_box = glm::min(box.hi, cell.hi) - glm::max(box.lo, cell.lo);
    const Vec3 by_clip = glm::min(part.hi, cell.hi) - glm::max(part.lo, cell.lo);
    tighter += (by_clip.x * by_clip.y * by_clip.z) < 0.5f * (by_box.x * by_box.y * by_box.z);
  }
  std::printf("%d of 2000 triangles reach the cell; the clipped part is under half the box's part for %d\n",
              clipped, tighter);
  EXPECT_GT(clipped, 200);
  EXPECT_GT(tighter, clipped / 4);
}

/// `small` triangles 0.1 across in a 10-unit cube, crossed by `long_ones` long diagonal triangles:
/// no object split separates the long ones from the small ones they pass, which is where
/// spatial splits pay (a floor under furniture, a beam through a room).
tracer::Geometry small_and_long_triangles(int small, int long_ones) {
  tracer::Geometry g = long_diagonal_triangles(long_ones, 6.0f);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f), e(-0.05f, 0.05f);
  for (int i = 0; i < small; ++i) {
    const Vec3 a(u(rng), u(rng), u(rng));
    g.triangles.push_back({a, a + Vec3(e(rng), e(rng), e(rng)), a + Vec3(e(rng), e(rng), e(rng)), 0});
  }
  g.finalize();
  return g;
}

/// The boxes of the leaves of `bvh` that reference each primitive.
std::vector<std::vector<accel::Aabb>> leaf_boxes_by_primitive(const accel::Bvh& bvh, std::size_t primitives) {
  std::vector<std::vector<accel::Aabb>> out(primitives);
  const auto nodes = bvh.nodes();
  const auto box_of = [&](std::uint32_t i) {
    return accel::Aabb{{nodes[i].lo[0], nodes[i].lo[1], nodes[i].lo[2]}, {nodes[i].hi[0], nodes[i].hi[1], nodes[i].hi[2]}};
  };
  std::vector<std::uint32_t> todo{0};
  while (!todo.empty()) {
    const std::uint32_t i = todo.back();
    todo.pop_back();
    if (nodes[i].is_leaf()) {
      for (std::uint32_t k = nodes[i].first; k < nodes[i].first + nodes[i].count; ++k)
        out[bvh.prim_ids()[k]].push_back(box_of(i));
      continue;
    }
    todo.push_back(nodes[i].first);
    todo.push_back(nodes[i].first + 1);
  }
  return out;
}

/// The boxes (as the node stores them, padded) of the leaves of a wide BVH that reference each
/// primitive.
template <int W>
std::vector<std::vector<accel::Aabb>> leaf_boxes_by_primitive(const accel::WideBvh<W>& bvh, std::size_t primitives) {
  std::vector<std::vector<accel::Aabb>> out(primitives);
  for (const accel::WideNode<W>& n : bvh.nodes())
    for (int i = 0; i < W; ++i) {
      if (n.count[i] == 0) continue;
      const accel::Aabb box{{n.planes[0][i], n.planes[2][i], n.planes[4][i]}, {n.planes[1][i], n.planes[3][i], n.planes[5][i]}};
      for (std::uint32_t k = n.child[i]; k < n.child[i] + n.count[i]; ++k) out[bvh.prim_ids()[k]].push_back(box);
    }
  return out;
}

/// Samples each triangle of `g` (its vertices included) and asserts that every sample lies in
/// the box of some leaf that references the triangle (`leaves`, by primitive).
void expect_every_point_in_a_leaf_holding_it(const tracer::Geometry& g,
                                             const std::vector<std::vector<accel::Aabb>>& leaves,
                                             const std::string& label) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> w(0.0f, 1.0f);
  for (std::size_t id = 0; id < g.triangles.size(); ++id) {
    const tracer::Triangle& t = g.triangles[id];
    ASSERT_FALSE(leaves[id].empty()) << label << ": triangle " << id << " is in no leaf";
    for (int k = 0; k < 64; ++k) {
      float a = w(rng), b = w(rng);
      if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
      // Corners and edges included: the samples end on the vertices.
      if (k < 3) a = float(k == 1), b = float(k == 2);
      const Vec3 q = t.p0 + a * (t.p1 - t.p0) + b * (t.p2 - t.p0);
      const bool held = std::any_of(leaves[id].begin(), leaves[id].end(),
                                    [&](const accel::Aabb& box) { return box.contains(accel::Aabb::of_point(q)); });
      ASSERT_TRUE(held) << label << ": triangle " << id << ", sample " << k;
    }
  }
}

TEST(SpatialSplits, EveryPointOfATriangleLiesInALeafThatHoldsIt) {
  const tracer::Geometry g = small_and_long_triangles(3000, 100);
  const auto boxes = g.primitive_bounds();
  accel::BuildLimits limits;
  limits.overlap = tracer::primitive_overlap(g);
  accel::BvhParams p;
  p.spatial_split_budget = 1.0f;
  const accel::Bvh bvh(boxes, p, limits);
  const accel::BuildStats& s = bvh.stats();
  std::printf("%llu references to %zu triangles, %llu leaves\n", static_cast<unsigned long long>(s.prim_refs),
              boxes.size(), static_cast<unsigned long long>(s.leaves));
  EXPECT_GT(s.prim_refs, boxes.size() + boxes.size() / 10) << "the splits cut few triangles";
  EXPECT_LE(s.prim_refs, 2 * boxes.size()) << "over the budget";
  EXPECT_EQ(s.nodes, 2 * s.leaves - 1);
  expect_every_point_in_a_leaf_holding_it(g, leaf_boxes_by_primitive(bvh, boxes.size()), "bvh");
}

template <int W>
void expect_wide_spatial_splits_hold_every_triangle_and_lower_the_sah_cost() {
  const tracer::Geometry g = small_and_long_triangles(3000, 100);
  const auto boxes = g.primitive_bounds();
  accel::BuildLimits limits;
  limits.overlap = tracer::primitive_overlap(g);
  const accel::WideBvh<W> plain(boxes, {}, limits);
  // The depth limit applies to the collapsed tree: a leaf there takes its binary subtree's refs.
  for (int depth : {64, 2, 1}) {
    accel::WideBvhParams<W> p;
    p.spatial_split_budget = 0.5f;
    p.max_depth = depth;
    const accel::WideBvh<W> bvh(boxes, p, limits);
    const accel::BuildStats& s = bvh.stats();
    const std::string label = std::string(accel::WideBvh<W>::kName) + " max_depth " + std::to_string(depth);
    std::printf("%s: %llu references to %zu triangles, %llu leaves, depth %d, SAH cost %.2f (%.2f without spatial splits)\n",
                label.c_str(), static_cast<unsigned long long>(s.prim_refs), boxes.size(),
                static_cast<unsigned long long>(s.leaves), s.max_depth_reached, s.sah_cost, plain.stats().sah_cost);
    EXPECT_EQ(s.prim_refs, bvh.prim_ids().size());
    EXPECT_GT(s.prim_refs, boxes.size() + boxes.size() / 20) << label << ": the splits cut few triangles";
    EXPECT_LE(double(s.prim_refs), std::floor(double(boxes.size()) * 1.5)) << label << ": over the budget";
    EXPECT_LE(s.max_depth_reached, depth) << label;
    if (depth == 64) {
      EXPECT_LT(s.sah_cost, 0.8 * plain.stats().sah_cost) << label;
    }
    expect_every_point_in_a_leaf_holding_it(g, leaf_boxes_by_primitive(bvh, boxes.size()), label);
  }
}

TEST(SpatialSplits, TheWideBvhsCollapseTheSplitTreeAndKeepEveryTriangle) {
  expect_wide_spatial_splits_hold_every_triangle_and_lower_the_sah_cost<4>();
  expect_wide_spatial_splits_hold_every_triangle_and_lower_the_sah_cost<8>();
}

TEST(SpatialSplits, LowerTheSahCostOfLongTrianglesAmongSmallOnesWithinTheBudget) {
  const tracer::Geometry g = small_and_long_triangles(3000, 100);
  const auto boxes = g.primitive_bounds();
  accel::BuildLimits limits;
  limits.overlap = tracer::primitive_overlap(g);
  for (float budget : {0.05f, 0.5f}) {
    accel::BvhParams plain, spatial;
    spatial.spatial_split_budget = budget;
    const accel::BuildStats a = accel::Bvh(boxes, plain, limits).stats();
    const accel::BuildStats b = accel::Bvh(boxes, spatial, limits).stats();
    std::printf("budget %.2f: SAH cost %.2f without spatial splits, %.2f with (%.3f references per triangle)\n",
                budget, a.sah_cost, b.sah_cost, b.duplication());
    EXPECT_EQ(a.prim_refs, boxes.size());
    EXPECT_LE(double(b.prim_refs), std::floor(double(boxes.size()) * (1.0 + budget)));
    EXPECT_GT(b.prim_refs, boxes.size());
    EXPECT_LT(b.sah_cost, (budget < 0.1f ? 0.8 : 0.6) * a.sah_cost);
  }
}

TEST(TriangleBox, ClippedCandidatesGiveTheSahKdTreeALowerCost) {
  // The faces of long diagonal triangles' boxes are poor planes.
  const tracer::Geometry g = long_diagonal_triangles(2000, 3.0f);
  const auto boxes = g.primitive_bounds();
  accel::BuildLimits limits;
  limits.overlap = tracer::primitive_overlap(g);
  double cost[2] = {};
  int i = 0;
  for (const char* candidates : {"boxes", "clipped"}) {
    const nlohmann::json knobs = {{"split", "sah"}, {"split_candidates", candidates}};
    cost[i++] = accel::stats_of(accel::make_accel("kdtree", knobs, boxes, limits)).sah_cost;
  }
  std::printf("SAH cost of the kd-tree: %.2f from box faces, %.2f from clipped parts\n", cost[0], cost[1]);
  EXPECT_LT(cost[1], 0.9 * cost[0]);
}

}  // namespace
