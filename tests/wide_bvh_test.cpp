// The wide BVHs (accel/wide_bvh/): tree invariants over the knobs for 4 and 8 children, depth 0
// as one leaf, the memory budget, a million spheres built quickly and compactly, closest-hit
// leaves that test their nearest primitive first, and shadow-ray packets that walk each ray as
// it would walk alone. Equality with naive on adversarial rays is the oracle test's job.

#include "accel/wide_bvh/wide_bvh.h"

#include "accel/accel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace {

using accel::Aabb;
using accel::Vec3;

std::vector<Aabb> scattered_boxes(int n, std::uint32_t seed, float extent = 5.0f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-extent, extent), r(0.05f, 0.15f);
  std::vector<Aabb> boxes;
  boxes.reserve(std::size_t(n));
  for (int i = 0; i < n; ++i) {
    const Vec3 c(u(rng), u(rng), u(rng));
    const float radius = r(rng);
    boxes.push_back({c - Vec3(radius), c + Vec3(radius)});
  }
  return boxes;
}

template <int W>
void check_tree(const accel::WideBvh<W>& bvh, std::span<const Aabb> boxes, const accel::WideBvhParams<W>& p) {
  std::vector<int> seen(boxes.size(), 0);
  for (std::uint32_t id : bvh.prim_ids()) seen[id]++;
  for (int s : seen) ASSERT_EQ(s, 1);
  const auto nodes = bvh.nodes();
  struct Item {
    std::uint32_t node;
    int depth;
  };
  std::vector<Item> todo{{0, 0}};
  std::uint64_t leaves = 0, prims = 0, visited = 0;
  while (!todo.empty()) {
    const Item it = todo.back();
    todo.pop_back();
    ++visited;
    const accel::WideNode<W>& n = nodes[it.node];
    int used = 0;
    for (int i = 0; i < W; ++i) {
      const bool empty = n.planes[0][i] > n.planes[1][i];
      if (empty) {
        EXPECT_EQ(n.count[i], 0u);
        continue;
      }
      ++used;
      if (n.count[i] > 0) {  // a leaf at depth it.depth + 1
        ++leaves;
        prims += n.count[i];
        ASSERT_LE(it.depth + 1, std::max(p.max_depth, 1));
        if (it.depth + 1 < p.max_depth) {
          EXPECT_LE(n.count[i], std::uint32_t(p.max_leaf_size));
        }
        for (std::uint32_t j = n.child[i]; j < n.child[i] + n.count[i]; ++j) {
          const Aabb& b = boxes[bvh.prim_ids()[j]];
          for (int a = 0; a < 3; ++a) {
            EXPECT_LE(n.planes[2 * a][i], b.lo[a]);
            EXPECT_GE(n.planes[2 * a + 1][i], b.hi[a]);
          }
        }
      } else {
        ASSERT_LT(n.child[i], nodes.size());
        ASSERT_GT(n.child[i], it.node);
        const accel::WideNode<W>& c = nodes[n.child[i]];
        for (int j = 0; j < W; ++j) {
          if (c.planes[0][j] > c.planes[1][j]) continue;
          for (int a = 0; a < 3; ++a) {
            EXPECT_LE(n.planes[2 * a][i], c.planes[2 * a][j]);
            EXPECT_GE(n.planes[2 * a + 1][i], c.planes[2 * a + 1][j]);
          }
        }
        todo.push_back({n.child[i], it.depth + 1});
      }
    }
    // Only the root may have a single child (one leaf with everything).
    if (it.node != 0) {
      EXPECT_GE(used, 2);
    }
  }
  EXPECT_EQ(prims, boxes.size());
  EXPECT_EQ(leaves, bvh.stats().leaves);
  EXPECT_EQ(visited, nodes.size());
  EXPECT_EQ(nodes.size(), bvh.stats().nodes);
}

template <int W>
void invariants_across_knobs() {
  const auto boxes = scattered_boxes(700, 3);
  for (int depth : {0, 1, 2, 5, 64})
    for (int leaf : {1, 3, 8, 16}) {
      accel::WideBvhParams<W> p;
      p.max_depth = depth;
      p.max_leaf_size = leaf;
      const accel::WideBvh<W> bvh(boxes, p);
      SCOPED_TRACE("depth " + std::to_string(depth) + " leaf " + std::to_string(leaf));
      check_tree(bvh, boxes, p);
    }
}

TEST(WideBvh, TreeInvariantsAcrossKnobs4) { invariants_across_knobs<4>(); }
TEST(WideBvh, TreeInvariantsAcrossKnobs8) { invariants_across_knobs<8>(); }

TEST(WideBvh, DepthZeroIsOneLeafAndNodesFillUp) {
  const auto boxes = scattered_boxes(300, 5);
  accel::WideBvhParams<8> p;
  p.max_depth = 0;
  const accel::Bvh8 one(boxes, p);
  EXPECT_EQ(one.stats().nodes, 1u);
  EXPECT_EQ(one.stats().leaves, 1u);
  EXPECT_EQ(one.stats().max_leaf_prims, 300u);
  // With default knobs an 8-wide tree needs far fewer nodes than a binary one.
  const accel::Bvh8 wide(boxes);
  const accel::Bvh binary(boxes);
  EXPECT_LT(wide.stats().nodes * 3, binary.stats().nodes);
}

TEST(WideBvh, LeafBoxesAreLeftOutWhenTheShapesFollowAndNothingElseChanges) {
  const auto boxes = scattered_boxes(5000, 9);
  const accel::Bvh8 with(boxes, {}, accel::BuildLimits{});
  accel::BuildLimits limits;
  limits.shapes_follow = true;
  accel::Bvh8 without(boxes, {}, limits);
  // The same tree, less the primitives' boxes (6 floats each).
  ASSERT_EQ(without.nodes().size(), with.nodes().size());
  EXPECT_EQ(std::memcmp(without.nodes().data(), with.nodes().data(), with.nodes().size_bytes()), 0);
  EXPECT_TRUE(std::ranges::equal(without.prim_ids(), with.prim_ids()));
  EXPECT_LE(without.stats().memory_bytes + 6 * sizeof(float) * boxes.size(), with.stats().memory_bytes);
  // Without the attach, its leaves call the leaf function for every primitive, and every ray
  // still finds the nearest box the other finds.
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const auto hit = [&](std::uint32_t id, accel::Ray& r) {
    const Aabb& b = boxes[id];
    float t0 = r.tmin, t1 = r.tmax;
    for (int a = 0; a < 3; ++a) {
      const float inv = 1.0f / r.dir[a];
      float tn = (b.lo[a] - r.org[a]) * inv, tf = (b.hi[a] - r.org[a]) * inv;
      if (tn > tf) std::swap(tn, tf);
      t0 = std::max(t0, tn);
      t1 = std::min(t1, tf);
    }
    if (t0 > t1) return false;
    r.tmax = t0;
    return true;
  };
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    accel::Ray a;
    a.org = Vec3(8.0f * u(rng), 8.0f * u(rng), -12.0f);
    a.dir = Vec3(0.3f * u(rng), 0.3f * u(rng), 1.0f);
    accel::Ray b = a;
    with.intersect(a, hit);
    without.intersect(b, hit);
    ASSERT_EQ(a.tmax, b.tmax) << "ray " << i;
    hits += a.tmax < accel::kInfinity ? 1 : 0;
  }
  EXPECT_GT(hits, 100);
  // With the spheres attached both are the same structure.
  std::vector<accel::SphereShape> spheres(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) spheres[i] = {boxes[i].center(), 0.5f * (boxes[i].hi.x - boxes[i].lo.x)};
  accel::Bvh8 attached(boxes, {}, accel::BuildLimits{});
  attached.attach_spheres(spheres);
  without.attach_spheres(spheres);
  EXPECT_EQ(without.stats().memory_bytes, attached.stats().memory_bytes);
}

TEST(WideBvh, MemoryBudgetErrorNamesTheKnob) {
  const auto boxes = scattered_boxes(1000, 7);
  try {
    accel::Bvh4(boxes, {}, accel::BuildLimits{2048, {}});
    FAIL() << "expected ConfigError";
  } catch (const knobs::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--max-memory"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("bvh4: ", 0), 0u) << e.what();
  }
}

/// Four unit boxes in a row along +z in one leaf, the nearest to a ray going +z last in id
/// order; the leaf function hits a box where the ray enters it.
struct BoxRow {
  std::vector<Aabb> boxes;
  BoxRow() {
    for (int i = 0; i < 4; ++i) {
      const float z = 2.0f * float(3 - i);
      boxes.push_back({Vec3(-1.0f, -1.0f, z), Vec3(1.0f, 1.0f, z + 1.0f)});
    }
  }
  bool hit(std::uint32_t id, accel::Ray& r) const {
    const float t = (boxes[id].lo.z - r.org.z) / r.dir.z;
    if (t > r.tmin && t < r.tmax) {
      r.tmax = t;
      return true;
    }
    return false;
  }
};

template <int W>
void nearest_leaf_primitive_first() {
  const BoxRow row;
  accel::WideBvhParams<W> p;
  p.max_depth = 0;  // one leaf
  const accel::WideBvh<W> bvh(row.boxes, p);
  accel::Ray ray;
  ray.org = Vec3(0.25f, -0.5f, -10.0f);
  // No zero component: packets of these rays go down the tree together (as a frustum).
  ray.dir = Vec3(1e-3f, 2e-3f, 1.0f);
  accel::TraversalCounters c;
  bvh.template intersect<true>(ray, [&](std::uint32_t id, accel::Ray& r) { return row.hit(id, r); }, &c);
  EXPECT_EQ(ray.tmax, 10.0f);  // box 3, at z = 0
  // Taken in id order the leaf would test all four, each nearer than the last.
  EXPECT_EQ(c.prims_tested, 1u);

  std::vector<accel::Ray> rays(16, ray);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    rays[i].org.x = -0.9f + 0.1f * float(i);
    rays[i].tmax = accel::kInfinity;
  }
  accel::TraversalCounters pc;
  bvh.template intersect_packet<true>(
      rays, [&](std::size_t, std::uint32_t id, accel::Ray& r) { return row.hit(id, r); }, &pc);
  for (const accel::Ray& r : rays) EXPECT_EQ(r.tmax, 10.0f);
  EXPECT_EQ(pc.prims_tested, rays.size());

  // Any hit stops at the first primitive it tests, whichever.
  accel::TraversalCounters ac;
  accel::Ray shadow = ray;
  shadow.tmax = accel::kInfinity;
  EXPECT_TRUE(bvh.template occluded<true>(shadow, [&](std::uint32_t id, accel::Ray& r) { return row.hit(id, r); }, &ac));
  EXPECT_EQ(ac.prims_tested, 1u);
}

TEST(WideBvh, ClosestHitTestsTheNearestLeafPrimitiveFirst4) { nearest_leaf_primitive_first<4>(); }
TEST(WideBvh, ClosestHitTestsTheNearestLeafPrimitiveFirst8) { nearest_leaf_primitive_first<8>(); }

/// Packets of shadow-like rays (random origins toward one point, t = 1 at it) and of random
/// rays (some with zero direction components, some unbounded) over random boxes whose leaf
/// function hits the sphere inside each box: occluded_packet must answer occluded() for each
/// ray, and each ray must meet the nodes and primitives its own walk meets (so the counters of
/// the packet equal the sum of the single rays').
template <int W>
void occluded_packet_walks_each_ray_as_alone() {
  const std::vector<Aabb> boxes = scattered_boxes(2000, 7, 4.0f);
  const accel::WideBvh<W> bvh(boxes);
  const auto hit = [&](std::uint32_t id, const accel::Ray& r) {
    const Vec3 c = (boxes[id].lo + boxes[id].hi) * 0.5f, oc = r.org - c;
    const float radius = (boxes[id].hi.x - boxes[id].lo.x) * 0.5f;
    const float a = glm::dot(r.dir, r.dir), b = glm::dot(oc, r.dir), k = glm::dot(oc, oc) - radius * radius;
    const float disc = b * b - a * k;
    if (disc < 0.0f) return false;
    const float t0 = (-b - std::sqrt(disc)) / a, t1 = (-b + std::sqrt(disc)) / a;
    return (t0 > r.tmin && t0 < r.tmax) || (t1 > r.tmin && t1 < r.tmax);
  };
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f);
  std::uniform_int_distribution<int> pick(0, 7);
  int occluded_rays = 0, open_rays = 0;
  for (int packet = 0; packet < 200; ++packet) {
    const bool shadow = packet % 2 == 0;
    const Vec3 light(u(rng), u(rng), u(rng));
    std::vector<accel::Ray> rays(packet % 7 == 0 ? 5 : 16);
    for (accel::Ray& r : rays) {
      r.org = Vec3(u(rng), u(rng), u(rng));
      if (shadow) {
        r.dir = light - r.org;
        r.tmin = 1e-4f;
        r.tmax = 1.0f;
      } else {
        r.dir = Vec3(u(rng), u(rng), u(rng));
        if (pick(rng) == 0) r.dir[pick(rng) % 3] = 0.0f;
        r.tmax = pick(rng) < 4 ? accel::kInfinity : 0.1f * float(pick(rng) + 1);
      }
    }
    accel::TraversalCounters single, together;
    std::uint32_t expected = 0;
    for (std::size_t i = 0; i < rays.size(); ++i)
      if (bvh.template occluded<true>(rays[i], [&](std::uint32_t id, accel::Ray& r) { return hit(id, r); }, &single))
        expected |= 1u << i;
    const std::uint32_t got = bvh.template occluded_packet<true>(
        rays, [&](std::size_t, std::uint32_t id, accel::Ray& r) { return hit(id, r); }, &together);
    ASSERT_EQ(got, expected) << "packet " << packet;
    EXPECT_EQ(together.rays, single.rays) << "packet " << packet;
    EXPECT_EQ(together.nodes_visited, single.nodes_visited) << "packet " << packet;
    EXPECT_EQ(together.boxes_tested, single.boxes_tested) << "packet " << packet;
    EXPECT_EQ(together.prims_tested, single.prims_tested) << "packet " << packet;
    occluded_rays += std::popcount(expected);
    open_rays += int(rays.size()) - std::popcount(expected);
  }
  // Both answers occur often enough to mean something.
  EXPECT_GT(occluded_rays, 500);
  EXPECT_GT(open_rays, 500);
}

TEST(WideBvh, OccludedPacketWalksEachRayAsAlone4) { occluded_packet_walks_each_ray_as_alone<4>(); }
TEST(WideBvh, OccludedPacketWalksEachRayAsAlone8) { occluded_packet_walks_each_ray_as_alone<8>(); }

/// Checks that the nodes lie in depth first order: a node's inner children are the next nodes
/// after everything its earlier children's subtrees hold, in slot order.
template <int W>
void expect_depth_first(std::span<const accel::WideNode<W>> nodes, std::uint32_t node, std::uint32_t& next) {
  std::vector<std::uint32_t> inner;
  for (int i = 0; i < W; ++i)
    if (nodes[node].count[i] == 0 && nodes[node].planes[0][i] <= nodes[node].planes[1][i])
      inner.push_back(nodes[node].child[i]);
  for (std::uint32_t child : inner) ASSERT_EQ(child, next++);
  for (std::uint32_t child : inner) expect_depth_first<W>(nodes, child, next);
}

template <int W>
void same_tree_at_any_thread_count() {
  // Large enough that ranges fork into tasks (accel/build_tasks.h) several levels deep and the
  // first passes bin in parallel; leaves of one primitive make the most nodes, which the tasks'
  // node slabs must hold without overlapping.
  const auto boxes = scattered_boxes(60'000, 13, 20.0f);
  for (int leaf : {accel::WideBvhParams<W>{}.max_leaf_size, 1}) {
    SCOPED_TRACE(testing::Message() << "max_leaf_size " << leaf);
    accel::WideBvhParams<W> one;
    one.max_leaf_size = leaf;
    const accel::WideBvh<W> reference(boxes, one);
    check_tree(reference, boxes, one);
    std::uint32_t next = 1;
    expect_depth_first<W>(reference.nodes(), 0, next);
    EXPECT_EQ(next, reference.nodes().size());
    for (int threads : {2, 3, 0}) {
      SCOPED_TRACE(threads);
      accel::WideBvhParams<W> p = one;
      p.build_threads = threads;
      const accel::WideBvh<W> bvh(boxes, p);
      ASSERT_EQ(bvh.nodes().size(), reference.nodes().size());
      EXPECT_EQ(std::memcmp(bvh.nodes().data(), reference.nodes().data(), reference.nodes().size_bytes()), 0);
      EXPECT_TRUE(std::ranges::equal(bvh.prim_ids(), reference.prim_ids()));
      EXPECT_EQ(bvh.stats().sah_cost, reference.stats().sah_cost);
      EXPECT_EQ(bvh.stats().leaves, reference.stats().leaves);
      EXPECT_EQ(bvh.stats().max_depth_reached, reference.stats().max_depth_reached);
    }
  }
}

TEST(WideBvh, TheTreeIsTheSameAtAnyThreadCount4) { same_tree_at_any_thread_count<4>(); }
TEST(WideBvh, TheTreeIsTheSameAtAnyThreadCount8) { same_tree_at_any_thread_count<8>(); }

TEST(WideBvh, AMillionSpheresBuildCompactly) {
  // The large-scene target: 10^6 random spheres, structure and sphere leaves together
  // at most 100 bytes per sphere. The time (< 1 s on an idle machine) is measured by
  // bench_trace's Build/random1M; here it only has to finish.
  const int n = 1'000'000;
  const auto boxes = scattered_boxes(n, 11, 100.0f);
  std::vector<accel::SphereShape> spheres(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) spheres[i] = {boxes[i].center(), 0.5f * (boxes[i].hi.x - boxes[i].lo.x)};
  accel::Bvh8 bvh(boxes);
  bvh.attach_spheres(spheres);
  EXPECT_TRUE(bvh.has_sphere_leaves());
  const double per_sphere = double(bvh.stats().memory_bytes) / n;
  EXPECT_LE(per_sphere, 100.0);
  RecordProperty("bytes_per_sphere", std::to_string(per_sphere));
  RecordProperty("build_ms", std::to_string(bvh.stats().build_ms));
}

}  // namespace
