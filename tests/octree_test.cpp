#include "accel/octree.h"

#include "sphere_oracle.h"

#include "accel/accel.h"

#include <gtest/gtest.h>

#include <bit>
#include <string>
#include <vector>

namespace {

using accel::Aabb;
using accel::Octree;
using accel::OctreeNode;
using accel::OctreeParams;
using accel::Placement;
using accel::Vec3;
using sphere_oracle::AxisPlane;
using sphere_oracle::SceneKind;

OctreeParams knobs(int depth, int leaf, Placement placement) {
  OctreeParams p;
  p.max_depth = depth;
  p.max_leaf_size = leaf;
  p.placement = placement;
  return p;
}

/// Calls fn(node index, cell, depth) for every stored cell.
template <class Fn>
void walk(const Octree& t, Fn&& fn, std::uint32_t node, const Aabb& cell, int depth) {
  fn(node, cell, depth);
  const OctreeNode& n = t.nodes()[node];
  const Vec3 mid = accel::cell_mid(cell);
  std::uint32_t child = n.first_child;
  for (unsigned c = 0; c < 8; ++c)
    if ((n.child_mask >> c) & 1u) walk(t, fn, child++, accel::child_cell(cell, mid, c), depth + 1);
}
template <class Fn>
void walk(const Octree& t, Fn&& fn) {
  walk(t, fn, 0, t.root_cell(), 0);
}

std::vector<AxisPlane> planes_of(const Octree& t) {
  std::vector<AxisPlane> out;
  walk(t, [&](std::uint32_t i, const Aabb& cell, int) {
    if (t.nodes()[i].is_leaf()) return;
    const Vec3 mid = accel::cell_mid(cell);
    for (int a = 0; a < 3; ++a) out.push_back({a, mid[a]});
  });
  for (int a = 0; a < 3; ++a) out.push_back({a, t.root_cell().lo[a]}), out.push_back({a, t.root_cell().hi[a]});
  return out;
}

/// Primitives stored in the subtree of `node`.
std::uint64_t subtree_prims(const Octree& t, std::uint32_t node) {
  const OctreeNode& n = t.nodes()[node];
  std::uint64_t sum = n.prim_count;
  for (int k = 0; k < std::popcount(n.child_mask); ++k) sum += subtree_prims(t, n.first_child + std::uint32_t(k));
  return sum;
}

TEST(Octree, RootCellIsACubeAroundTheScene) {
  const auto g = sphere_oracle::make_scene(SceneKind::Line, 1);
  const std::vector<Aabb> boxes = g.primitive_bounds();
  const Octree t(boxes);
  const Vec3 e = t.root_cell().extent();
  EXPECT_FLOAT_EQ(e.x, e.z);
  EXPECT_FLOAT_EQ(e.y, e.z);
  for (const Aabb& b : boxes) EXPECT_TRUE(t.root_cell().contains(b));
}

TEST(Octree, DepthZeroIsOneLeafHoldingEveryPrimitive) {
  const auto g = sphere_oracle::make_scene(SceneKind::Uniform, 1);
  const Octree t(g.primitive_bounds(), knobs(0, 1, Placement::Leaves));
  const accel::BuildStats& s = t.stats();
  EXPECT_EQ(s.nodes, 1u);
  EXPECT_EQ(s.leaves, 1u);
  EXPECT_EQ(s.prim_refs, g.spheres.size());
  EXPECT_EQ(s.primitives, g.spheres.size());
  EXPECT_EQ(s.max_leaf_prims, g.spheres.size());
  EXPECT_EQ(s.max_depth_reached, 0);
  EXPECT_DOUBLE_EQ(s.sah_cost, double(g.spheres.size()));
  EXPECT_EQ(s.memory_bytes, sizeof(OctreeNode) + 4u * g.spheres.size());
}

TEST(Octree, NeverStoresAnEmptyChild) {
  for (SceneKind kind : {SceneKind::Uniform, SceneKind::HugeAmongTiny, SceneKind::Line}) {
    const auto g = sphere_oracle::make_scene(kind, 2);
    for (Placement placement : {Placement::Leaves, Placement::EveryLevel}) {
      const Octree t(g.primitive_bounds(), knobs(6, 1, placement));
      EXPECT_EQ(t.stats().empty_leaves, 0u);
      int stored = 0;
      walk(t, [&](std::uint32_t i, const Aabb&, int) {
        ++stored;
        EXPECT_GT(subtree_prims(t, i), 0u) << "node " << i;
      });
      EXPECT_EQ(std::uint64_t(stored), t.stats().nodes);  // every node is reachable
      // The line scene leaves most of the cube empty: far fewer than 8 children per split.
      if (kind == SceneKind::Line && placement == Placement::Leaves) {
        EXPECT_LT(t.stats().nodes, 8u * (t.stats().nodes - t.stats().leaves));
      }
    }
  }
}

TEST(Octree, EveryLevelStoresEachPrimitiveOnce) {
  for (SceneKind kind : {SceneKind::Uniform, SceneKind::HugeAmongTiny, SceneKind::Duplicates}) {
    const auto g = sphere_oracle::make_scene(kind, 3);
    const Octree t(g.primitive_bounds(), knobs(12, 1, Placement::EveryLevel));
    EXPECT_EQ(t.stats().prim_refs, g.spheres.size());
    EXPECT_EQ(t.stats().duplication(), 1.0);
    const Octree dup(g.primitive_bounds(), knobs(3, 1, Placement::Leaves));
    EXPECT_GT(dup.stats().duplication(), 1.0) << sphere_oracle::scene_name(kind);
  }
}

TEST(Octree, LeavesRespectLeafSizeUnlessDepthStopsThem) {
  const auto g = sphere_oracle::make_scene(SceneKind::Uniform, 4);
  for (Placement placement : {Placement::Leaves, Placement::EveryLevel}) {
    for (int depth : {2, 4, 8}) {
      for (int leaf : {1, 4, 16}) {
        const Octree t(g.primitive_bounds(), knobs(depth, leaf, placement));
        std::uint64_t leaves = 0, biggest = 0;
        int deepest = 0;
        walk(t, [&](std::uint32_t i, const Aabb& cell, int d) {
          const OctreeNode& n = t.nodes()[i];
          deepest = std::max(deepest, d);
          if (!n.is_leaf()) return;
          ++leaves;
          biggest = std::max<std::uint64_t>(biggest, n.prim_count);
          for (std::uint32_t k = n.prim_begin; k < n.prim_begin + n.prim_count; ++k)
            EXPECT_TRUE(cell.overlaps(g.primitive_bounds()[t.prim_ids()[k]]));
          // Over the leaf size only at max_depth, or (every_level) when all of them straddle.
          if (n.prim_count > std::uint32_t(leaf) && d < depth) {
            EXPECT_EQ(placement, Placement::EveryLevel);
          }
        });
        EXPECT_LE(deepest, depth);
        EXPECT_EQ(t.stats().leaves, leaves);
        EXPECT_EQ(t.stats().max_leaf_prims, biggest);
        EXPECT_EQ(t.stats().max_depth_reached, deepest);
      }
    }
  }
}

TEST(Octree, RejectsBadKnobsWithOneLineNamingTheKey) {
  const std::vector<Aabb> one{Aabb{Vec3(0.0f), Vec3(1.0f)}};
  auto error_of = [&](const nlohmann::json& j) -> std::string {
    try {
      accel::make_accel("octree", j, one);
    } catch (const knobs::ConfigError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(error_of({{"max_leaf_size", 0}}),
            "octree: knob 'max_leaf_size' must be in [1, 2147483647], got 0");
  EXPECT_EQ(error_of({{"max_depth", 65}}), "octree: knob 'max_depth' must be in [0, 64], got 65");
  EXPECT_EQ(error_of({{"max_depth", 2.5}}), "octree: knob 'max_depth' must be an integer, got 2.5");
  EXPECT_EQ(error_of({{"split", "sah"}}), "octree: unknown knob 'split' (its knobs: max_depth, max_leaf_size, placement)");
  EXPECT_EQ(error_of({{"placement", 1}}),
            "octree: knob 'placement' must be one of leaves|every_level, got 1");
  OctreeParams direct;
  direct.max_depth = -1;
  EXPECT_THROW(Octree(one, direct), knobs::ConfigError);
}

TEST(Octree, KnobsRoundTripThroughJson) {
  const OctreeParams p = knobs(5, 3, Placement::EveryLevel);
  const nlohmann::json j = p;
  EXPECT_EQ(j, nlohmann::json({{"max_depth", 5}, {"max_leaf_size", 3}, {"placement", "every_level"}}));
  const accel::AnyAccel a = accel::make_accel("octree", j, std::vector<Aabb>{});
  EXPECT_EQ(accel::params_of(a), j);
  EXPECT_EQ(accel::name_of(a), "octree");
}

TEST(Octree, MemoryBudgetStopsTheDepth20Explosion) {
  // Large overlapping spheres: with `leaves` every one of them is in nearly every cell, and at
  // depth 20 the tree would need ~8^20 cells.
  tracer::Geometry g;
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f);
  for (int i = 0; i < 200; ++i) g.spheres.push_back({Vec3(u(rng), u(rng), u(rng)), 4.0f, 0});
  g.finalize();
  try {
    Octree(g.primitive_bounds(), knobs(20, 8, Placement::Leaves), accel::BuildLimits{64ull << 20, {}});
    FAIL() << "no error";
  } catch (const knobs::ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              "octree: build needs more than 64.0 MiB (--max-memory); lower max_depth or raise "
              "max_leaf_size, or use placement every_level");
  }
  // The error is the whole guarantee: the builder refuses once its nodes would pass the budget,
  // so it never holds more than the budget, however deep the tree could grow. (No wall-time
  // bound: speed belongs in benchmarks.)
  const Octree fits(g.primitive_bounds(), knobs(20, 8, Placement::EveryLevel), accel::BuildLimits{64ull << 20, {}});
  EXPECT_EQ(fits.stats().prim_refs, g.spheres.size());
}

// Every knob combination of the grid answers every ray exactly as naive does.
class OctreeOracle : public ::testing::TestWithParam<SceneKind> {};

TEST_P(OctreeOracle, MatchesNaiveOverTheKnobGrid) {
  const auto g = sphere_oracle::make_scene(GetParam(), 6);
  const std::vector<Aabb> boxes = g.primitive_bounds();
  int checked = 0;
  for (Placement placement : {Placement::Leaves, Placement::EveryLevel})
    for (int depth : {0, 1, 2, 3, 5, 7})
      for (int leaf : {1, 2, 5, 16}) {
        const Octree t(boxes, knobs(depth, leaf, placement), accel::BuildLimits{256ull << 20, {}});
        const auto rays = sphere_oracle::make_rays(g, planes_of(t), std::uint32_t(checked));
        const std::string label = nlohmann::json(t.params()).dump();
        if (checked++ % 5 == 0)
          EXPECT_TRUE(sphere_oracle::matches_naive<true>(g, t, rays)) << label;
        else
          EXPECT_TRUE(sphere_oracle::matches_naive(g, t, rays)) << label;
      }
}

INSTANTIATE_TEST_SUITE_P(Scenes, OctreeOracle,
                         ::testing::Values(SceneKind::Uniform, SceneKind::HugeAmongTiny,
                                           SceneKind::Line, SceneKind::Duplicates,
                                           SceneKind::Grid, SceneKind::Single, SceneKind::Empty),
                         [](const auto& scene) { return std::string(sphere_oracle::scene_name(scene.param)); });

}  // namespace
