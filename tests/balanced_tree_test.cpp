// The paper's balanced photon tree (photon/balanced_tree.h): a left-balanced heap of depth
// ceil(log2(N + 1)), every node the median of its cell along the cell's longest axis.

#include "photon/balanced_tree.h"
#include "photon/photon_tree_params.h"

#include "accel/accel.h"
#include "accel/geometry.h"
#include "photon_sets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace {

using photon::BalancedTree;
using photon::Photon;
using photon_sets::SetKind;

/// Checks the subtree of `node` in `cell`; returns its depth (levels).
int check_node(const BalancedTree& t, std::uint32_t node, const accel::Aabb& cell,
               std::vector<int>& seen, std::string& error) {
  const std::uint32_t n = std::uint32_t(t.size());
  if (node > n || !error.empty()) return 0;
  const Photon& p = t.storage()[node];
  seen[t.ids()[node]]++;
  for (int a = 0; a < 3; ++a)
    if (p.position[a] < cell.lo[a] || p.position[a] > cell.hi[a]) error = "photon outside its cell";
  const int axis = p.flags & 3;
  if (2 * node > n) {
    if (axis != 3) error = "leaf not flagged 3 at node " + std::to_string(node);
    return 1;
  }
  if (axis != cell.longest_axis()) error = "split axis is not the cell's longest at node " + std::to_string(node);
  if (axis == 3) return 0;
  // The median property: everything below-left is <= the node, everything below-right >=.
  const float split = p.position[axis];
  std::vector<std::uint32_t> stack{2 * node};
  std::size_t left_count = 0, right_count = 0;
  while (!stack.empty()) {
    const std::uint32_t i = stack.back();
    stack.pop_back();
    if (i > n) continue;
    if (t.storage()[i].position[axis] > split) error = "left subtree above the median at node " + std::to_string(node);
    ++left_count;
    stack.push_back(2 * i), stack.push_back(2 * i + 1);
  }
  stack.push_back(2 * node + 1);
  while (!stack.empty()) {
    const std::uint32_t i = stack.back();
    stack.pop_back();
    if (i > n) continue;
    if (t.storage()[i].position[axis] < split) error = "right subtree below the median at node " + std::to_string(node);
    ++right_count;
    stack.push_back(2 * i), stack.push_back(2 * i + 1);
  }
  // Left-balanced: the left subtree is never smaller, and at most twice the right plus one.
  if (left_count < right_count) error = "left subtree smaller than right at node " + std::to_string(node);
  accel::Aabb lower = cell, upper = cell;
  lower.hi[axis] = split;
  upper.lo[axis] = split;
  return 1 + std::max(check_node(t, 2 * node, lower, seen, error),
                      check_node(t, 2 * node + 1, upper, seen, error));
}

TEST(BalancedTree, MedianAtEveryNodeAndDepthCeilLog2) {
  for (const SetKind kind : photon_sets::kAllKinds) {
    for (std::size_t n = 0; n <= 300; n += (n < 40 ? 1 : 37)) {
      const auto photons = photon_sets::make_set(kind, n, std::uint32_t(n + 100));
      const BalancedTree t(photons);
      ASSERT_EQ(t.size(), n);
      accel::Aabb root;
      for (const Photon& p : photons) root.grow(p.position);
      std::vector<int> seen(n, 0);
      std::string error;
      const int depth = n ? check_node(t, 1, root, seen, error) : 0;
      ASSERT_EQ(error, "") << photon_sets::name_of(kind) << " N=" << n;
      const int want = int(std::ceil(std::log2(double(n) + 1.0)));
      EXPECT_EQ(depth, want) << photon_sets::name_of(kind) << " N=" << n;
      EXPECT_EQ(t.stats().depth, want) << photon_sets::name_of(kind) << " N=" << n;
      EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(n)) << "not a permutation";
      for (std::uint32_t i = 1; i <= n; ++i) {
        EXPECT_EQ(t.storage()[i].position, photons[t.ids()[i]].position);
        EXPECT_EQ(t.storage()[i].power_bits, photons[t.ids()[i]].power_bits);
      }
    }
  }
}

TEST(BalancedTree, LargeTreeDepthAndStats) {
  const auto photons = photon_sets::make_set(SetKind::Clustered, 100000, 5);
  const BalancedTree t(photons);
  EXPECT_EQ(t.stats().depth, 17);  // ceil(log2(100001))
  EXPECT_EQ(t.stats().nodes, 100000u);
  EXPECT_EQ(t.stats().leaves, 50000u);
  EXPECT_GE(t.stats().memory_bytes, 100001u * 24u);
}

}  // namespace

namespace {

TEST(BalancedTree, SameTreeOnAnyNumberOfThreads) {
  const auto photons = photon_sets::make_set(SetKind::Clustered, 200000, 9);
  const BalancedTree one(photons, 1);
  for (const int threads : {2, 7, 0}) {
    const BalancedTree many(photons, threads);
    ASSERT_EQ(many.size(), one.size());
    EXPECT_EQ(many.stats().depth, one.stats().depth);
    bool same = true;
    for (std::size_t i = 1; i <= one.size() && same; ++i)
      same = std::memcmp(&many.storage()[i], &one.storage()[i], sizeof(Photon)) == 0 &&
             many.ids()[i] == one.ids()[i];
    EXPECT_TRUE(same) << threads << " threads";
  }
}

TEST(BalancedTree, ParamsJsonNamesTheKnob) {
  const auto error = [](const char* text) -> std::string {
    try {
      nlohmann::json::parse(text).get<photon::PhotonTreeParams>();
    } catch (const knobs::ConfigError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(error(R"({"photon_tree": "kd"})"),
            "photon map: knob 'photon_tree' must be one of "
            "balanced|sliding_midpoint|median_buckets|brute_force, got \"kd\"");
  EXPECT_EQ(error(R"({"leaf_size": 0})"), "photon map: knob 'leaf_size' must be in [1, 256], got 0");
  EXPECT_EQ(error(R"({"build_threads": -1})"),
            "photon map: knob 'build_threads' must be in [0, 256], got -1");
  EXPECT_EQ(error(R"({"leafsize": 4})"),
            "photon map: unknown knob 'leafsize' (its knobs: photon_tree, leaf_size, build_threads)");
  const photon::PhotonTreeParams p =
      nlohmann::json(photon::PhotonTreeParams{photon::PhotonTreeKind::MedianBuckets, 24, 3})
          .get<photon::PhotonTreeParams>();
  EXPECT_EQ(p.photon_tree, photon::PhotonTreeKind::MedianBuckets);
  EXPECT_EQ(p.leaf_size, 24);
  EXPECT_EQ(p.build_threads, 3);
}

}  // namespace
