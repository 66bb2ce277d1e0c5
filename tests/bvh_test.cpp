#include "accel/bvh.h"

#include "accel/accel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

namespace {

using accel::Aabb;
using accel::Bvh;
using accel::BvhParams;
using accel::Ray;
using accel::Vec3;

std::vector<Aabb> random_boxes(int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f), r(0.05f, 0.15f);
  std::vector<Aabb> boxes;
  for (int i = 0; i < n; ++i) {
    const Vec3 c(u(rng), u(rng), u(rng));
    const float radius = r(rng);
    boxes.push_back({c - Vec3(radius), c + Vec3(radius)});
  }
  return boxes;
}

/// Checks the tree's invariants: every id once, children inside parents, leaf sizes, depth.
void check_tree(const Bvh& bvh, std::span<const Aabb> boxes, const BvhParams& p) {
  std::vector<int> seen(boxes.size(), 0);
  for (std::uint32_t id : bvh.prim_ids()) seen[id]++;
  for (int s : seen) ASSERT_EQ(s, 1);
  const auto nodes = bvh.nodes();
  struct Item {
    std::uint32_t node;
    int depth;
  };
  std::vector<Item> todo{{0, 0}};
  std::uint64_t leaves = 0, prims = 0;
  while (!todo.empty()) {
    const Item it = todo.back();
    todo.pop_back();
    const accel::BvhNode& n = nodes[it.node];
    ASSERT_LE(it.depth, p.max_depth);
    if (n.is_leaf()) {
      ++leaves;
      prims += n.count;
      if (it.depth < p.max_depth) {
        EXPECT_LE(n.count, std::uint32_t(p.max_leaf_size));
      }
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
        const Aabb& b = boxes[bvh.prim_ids()[i]];
        for (int a = 0; a < 3; ++a) {
          EXPECT_LE(n.lo[a], b.lo[a]);
          EXPECT_GE(n.hi[a], b.hi[a]);
        }
      }
    } else {
      ASSERT_LT(n.first + 1, nodes.size());
      for (std::uint32_t c : {n.first, n.first + 1}) {
        for (int a = 0; a < 3; ++a) {
          EXPECT_LE(n.lo[a], nodes[c].lo[a]);
          EXPECT_GE(n.hi[a], nodes[c].hi[a]);
        }
        todo.push_back({c, it.depth + 1});
      }
    }
  }
  EXPECT_EQ(prims, boxes.size());
  EXPECT_EQ(leaves, bvh.stats().leaves);
  EXPECT_EQ(nodes.size() - 1, bvh.stats().nodes);  // less the unused node 1
}

TEST(Bvh, TreeInvariantsAcrossKnobs) {
  const auto boxes = random_boxes(500, 1);
  for (int depth : {0, 1, 3, 8, 64})
    for (int leaf : {1, 2, 4, 16})
      for (int bins : {8, 32}) {
        BvhParams p;
        p.max_depth = depth;
        p.max_leaf_size = leaf;
        p.bins = bins;
        const Bvh bvh(boxes, p);
        SCOPED_TRACE(testing::Message() << "depth " << depth << " leaf " << leaf << " bins " << bins);
        check_tree(bvh, boxes, p);
      }
}

TEST(Bvh, DepthZeroIsOneLeafHoldingEverything) {
  const auto boxes = random_boxes(300, 2);
  BvhParams p;
  p.max_depth = 0;
  const Bvh bvh(boxes, p);
  EXPECT_EQ(bvh.stats().nodes, 1u);
  EXPECT_EQ(bvh.stats().leaves, 1u);
  EXPECT_EQ(bvh.stats().max_leaf_prims, 300u);
  EXPECT_EQ(bvh.stats().max_depth_reached, 0);
  EXPECT_DOUBLE_EQ(bvh.stats().sah_cost, 300.0);
  EXPECT_DOUBLE_EQ(bvh.stats().duplication(), 1.0);
}

TEST(Bvh, StatisticsAreFilled) {
  const auto boxes = random_boxes(1000, 3);
  const Bvh bvh(boxes);
  const accel::BuildStats& s = bvh.stats();
  EXPECT_EQ(s.primitives, 1000u);
  EXPECT_EQ(s.prim_refs, 1000u);
  EXPECT_EQ(s.empty_leaves, 0u);
  EXPECT_EQ(s.nodes, 2 * s.leaves - 1);  // a binary tree
  EXPECT_GT(s.max_depth_reached, 5);
  EXPECT_LE(s.max_leaf_prims, 4u);
  EXPECT_NEAR(s.mean_leaf_prims, 1000.0 / double(s.leaves), 1e-9);
  EXPECT_EQ(s.memory_bytes, (s.nodes + 1) * 32 + 1000 * 4);  // with the unused node 1
  // SAH cost: one traversal per inner node weighted by area, far below the 1000 of one leaf.
  EXPECT_GT(s.sah_cost, 1.0);
  EXPECT_LT(s.sah_cost, 100.0);
  EXPECT_GT(s.build_ms, 0.0);
}

/// Checks that the nodes lie in depth-first order, left child first: each inner node's sibling
/// pair is the next pair after everything its earlier siblings' subtrees hold.
void expect_depth_first(std::span<const accel::BvhNode> nodes, std::uint32_t node, std::uint32_t& next_pair) {
  if (nodes[node].is_leaf()) return;
  ASSERT_EQ(nodes[node].first, next_pair);
  next_pair += 2;
  expect_depth_first(nodes, nodes[node].first, next_pair);
  expect_depth_first(nodes, nodes[node].first + 1, next_pair);
}

TEST(Bvh, TheTreeIsTheSameAtAnyThreadCount) {
  // Large enough that ranges fork into tasks (accel/build_tasks.h) many levels deep and the
  // first passes bin in parallel. Leaves of one primitive make the most nodes a tree can have
  // (2n - 1), which the tasks' node slabs must hold without overlapping.
  const auto boxes = random_boxes(60'000, 9);
  for (int leaf : {4, 1}) {
    SCOPED_TRACE(testing::Message() << "max_leaf_size " << leaf);
    BvhParams one;
    one.max_leaf_size = leaf;
    const Bvh reference(boxes, one);
    check_tree(reference, boxes, one);
    std::uint32_t next_pair = 2;
    expect_depth_first(reference.nodes(), 0, next_pair);
    EXPECT_EQ(next_pair, reference.nodes().size());
    if (leaf == 1) {
      EXPECT_EQ(reference.stats().nodes, 2 * boxes.size() - 1);
    }
    for (int threads : {2, 3, 0}) {
      SCOPED_TRACE(threads);
      BvhParams p = one;
      p.build_threads = threads;
      const Bvh bvh(boxes, p);
      ASSERT_EQ(bvh.nodes().size(), reference.nodes().size());
      EXPECT_EQ(std::memcmp(bvh.nodes().data(), reference.nodes().data(), reference.nodes().size_bytes()), 0);
      EXPECT_TRUE(std::ranges::equal(bvh.prim_ids(), reference.prim_ids()));
      EXPECT_EQ(bvh.stats().sah_cost, reference.stats().sah_cost);
      EXPECT_EQ(bvh.stats().leaves, reference.stats().leaves);
      EXPECT_EQ(bvh.stats().max_depth_reached, reference.stats().max_depth_reached);
      EXPECT_EQ(bvh.stats().max_leaf_prims, reference.stats().max_leaf_prims);
    }
  }
}

TEST(Bvh, ZeroPrimitives) {
  const Bvh bvh(std::span<const Aabb>{});
  EXPECT_EQ(bvh.stats().nodes, 0u);
  Ray ray;
  int calls = 0;
  auto leaf = [&](std::uint32_t, Ray&) {
    ++calls;
    return true;
  };
  bvh.intersect(ray, leaf);
  EXPECT_FALSE(bvh.occluded(ray, leaf));
  EXPECT_EQ(calls, 0);
}

TEST(Bvh, IdenticalCentroidsStillRespectLeafSize) {
  std::vector<Aabb> boxes(37, Aabb{Vec3(1.0f), Vec3(2.0f)});
  BvhParams p;
  p.max_leaf_size = 2;
  const Bvh bvh(boxes, p);
  check_tree(bvh, boxes, p);
  EXPECT_LE(bvh.stats().max_leaf_prims, 2u);
}

// The leaf callback receives the original primitive ids, and ordered traversal with the
// callback shortening tmax finds the nearest box along the ray.
TEST(Bvh, ClosestAndAnyHitThroughLeafCallback) {
  std::vector<Aabb> boxes;
  for (int i = 0; i < 64; ++i) {  // a row of unit boxes along +z, ids shuffled in space
    const float z = float((i * 37) % 64) * 2.0f;
    boxes.push_back({Vec3(-0.5f, -0.5f, z), Vec3(0.5f, 0.5f, z + 1.0f)});
  }
  const Bvh bvh(boxes, BvhParams{});
  auto slab = [&](std::uint32_t id, Ray& r) {
    const float t = (boxes[id].lo.z - r.org.z) / r.dir.z;
    if (t > r.tmin && t < r.tmax) {
      r.tmax = t;
      return true;
    }
    return false;
  };
  Ray ray;
  ray.org = Vec3(0.0f, 0.0f, 9.5f);
  ray.dir = Vec3(0.0f, 0.0f, 1.0f);
  accel::TraversalCounters c;
  bvh.intersect<true>(ray, slab, &c);
  EXPECT_FLOAT_EQ(ray.tmax, 0.5f);  // the box starting at z = 10
  EXPECT_EQ(c.rays, 1u);
  EXPECT_LT(c.prims_tested, 20u);  // front to back: stops early
  EXPECT_GT(c.nodes_visited, 0u);
  EXPECT_GE(c.boxes_tested, c.nodes_visited);

  Ray short_ray = ray;
  short_ray.tmax = 0.25f;
  short_ray.org = Vec3(0.0f, 0.0f, 9.5f);
  EXPECT_FALSE(bvh.occluded(short_ray, slab));
  short_ray.tmax = 1.0f;
  EXPECT_TRUE(bvh.occluded(short_ray, slab));
}

TEST(Bvh, MemoryBudgetIsHonoured) {
  const auto boxes = random_boxes(1000, 4);
  try {
    Bvh(boxes, BvhParams{}, accel::BuildLimits{1000, {}});
    FAIL() << "expected ConfigError";
  } catch (const knobs::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--max-memory"), std::string::npos) << e.what();
  }
}

TEST(Bvh, InvalidParamsInCodeAreRejected) {
  const auto boxes = random_boxes(10, 5);
  BvhParams p;
  p.bins = 2;
  EXPECT_THROW(Bvh(boxes, p), knobs::ConfigError);
  p = {};
  p.max_depth = 65;
  EXPECT_THROW(Bvh(boxes, p), knobs::ConfigError);
  p = {};
  p.max_leaf_size = 0;
  EXPECT_THROW(Bvh(boxes, p), knobs::ConfigError);
}

TEST(Bvh, BuildsEightThousandSpheresQuickly) {
  // The grid of the paper's spheres8000 scene; the 5 ms target is for Release builds, so the
  // test allows a wide margin (sanitizers, a loaded machine) and the benchmark reports the time.
  std::vector<Aabb> boxes;
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> jitter(-0.1f, 0.1f), r(0.05f, 0.15f);
  for (int x = 0; x < 20; ++x)
    for (int y = 0; y < 20; ++y)
      for (int z = 0; z < 20; ++z) {
        const Vec3 c = Vec3(float(x), float(y), float(z)) * 0.5f + Vec3(jitter(rng), jitter(rng), jitter(rng));
        const float radius = r(rng);
        boxes.push_back({c - Vec3(radius), c + Vec3(radius)});
      }
  double best = 1e9;
  for (int i = 0; i < 3; ++i) best = std::min(best, Bvh(boxes).stats().build_ms);
  EXPECT_LT(best, 100.0);
  RecordProperty("build_ms_8000", std::to_string(best));
}

}  // namespace
