#pragma once
// The recursion shared by the bucket-tree builders (sliding_midpoint_builder.cpp,
// median_bucket_builder.cpp): each supplies only its split rule. Internal to photon/.

#include "bucket_tree.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <span>
#include <vector>

namespace photon::bucket_detail {

/// A photon's position and original index, what the partitioning moves (16 bytes).
struct Item {
  float p[3];
  std::uint32_t id;
};

/// A split of items[begin, end): items[begin, mid) have p[axis] <= plane <= items[mid, end).
struct Split {
  int axis;
  float plane;
  std::uint32_t mid;
};

/// Builds a bucket tree. `rule(items, begin, end, cell)` partitions a cell's items and returns
/// the split, with begin < mid < end; it is called only for cells of more than leaf_size
/// photons and non-zero extent.
template <class Rule>
BucketTree build_bucket_tree(std::span<const Photon> photons, int leaf_size, Rule&& rule) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::uint32_t n = std::uint32_t(photons.size());
  const std::uint32_t leaf = std::uint32_t(std::max(1, leaf_size));
  std::vector<Item> items(n);
  accel::Aabb bounds;
  for (std::uint32_t i = 0; i < n; ++i) {
    const Vec3& p = photons[i].position;
    items[i] = {{p.x, p.y, p.z}, i};
    bounds.grow(p);
  }
  std::vector<accel::KdNode> nodes;
  nodes.reserve(2 * (std::size_t(n) / leaf + 1));
  PhotonTreeStats stats;
  const auto recurse = [&](auto& self, std::uint32_t begin, std::uint32_t end,
                           const accel::Aabb& cell, int depth) -> void {
    stats.depth = std::max(stats.depth, depth + 1);
    const std::uint32_t count = end - begin;
    const int axis = cell.longest_axis();
    // A leaf: small enough, too deep, or a cell of zero size (coincident photons).
    if (count <= leaf || depth >= BucketTree::kMaxDepth || !(cell.hi[axis] - cell.lo[axis] > 0.0f)) {
      nodes.push_back(accel::KdNode::leaf(begin, count));
      stats.leaves++;
      stats.max_leaf_photons = std::max<std::uint64_t>(stats.max_leaf_photons, count);
      return;
    }
    const Split s = rule(items.data(), begin, end, cell);
    const std::size_t self_index = nodes.size();
    nodes.emplace_back();
    accel::Aabb lower = cell, upper = cell;
    lower.hi[s.axis] = s.plane;
    upper.lo[s.axis] = s.plane;
    self(self, begin, s.mid, lower, depth + 1);
    nodes[self_index] = accel::KdNode::inner(s.axis, s.plane, std::uint32_t(nodes.size()));
    self(self, s.mid, end, upper, depth + 1);
  };
  if (n > 0) recurse(recurse, 0, n, bounds, 0);
  std::vector<Photon> stored(n);
  std::vector<std::uint32_t> ids(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    stored[i] = photons[items[i].id];
    stored[i].flags = 3;
    ids[i] = items[i].id;
  }
  stats.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return BucketTree(std::move(stored), std::move(ids), std::move(nodes), bounds, stats);
}

}  // namespace photon::bucket_detail
