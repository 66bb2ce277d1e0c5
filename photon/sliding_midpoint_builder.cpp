// Builds the bucket tree by the sliding-midpoint rule (Maneewongvatana and Mount, "It's okay to
// be skinny, if your friends are fat", 1999): split the cell's longest axis at its midpoint; when
// every photon lies on one side, slide the plane to the nearest photon and give that photon to
// the empty side. Cells never become empty, and thin clusters are cut off quickly instead of
// being halved level by level. Unlike the median tree, the result is not balanced.

#include "bucket_tree.h"

#include <algorithm>
#include <chrono>

namespace photon {

namespace {

struct Item {
  float p[3];
  std::uint32_t id;
};

class Builder {
 public:
  Builder(int leaf_size, std::vector<accel::KdNode>& nodes, std::vector<Item>& order)
      : leaf_size_(std::uint32_t(leaf_size)), nodes_(nodes), order_(order) {}

  /// Builds the subtree of items[begin, end) in `cell`; items end up in leaf order.
  void build(std::uint32_t begin, std::uint32_t end, accel::Aabb cell, int depth) {
    stats_depth_ = std::max(stats_depth_, depth + 1);
    const std::uint32_t n = end - begin;
    const int axis = cell.longest_axis();
    const float extent = cell.hi[axis] - cell.lo[axis];
    // A leaf: small enough, too deep, or a cell of zero size (coincident photons).
    if (n <= leaf_size_ || depth >= BucketTree::kMaxDepth || !(extent > 0.0f)) {
      nodes_.push_back(accel::KdNode::leaf(begin, n));
      leaves_++;
      max_leaf_ = std::max<std::uint64_t>(max_leaf_, n);
      return;
    }
    Item* items = order_.data();
    float split = cell.lo[axis] + 0.5f * extent;
    Item* mid = std::partition(items + begin, items + end,
                               [&](const Item& it) { return it.p[axis] < split; });
    if (mid == items + begin) {
      // Every photon at or above the plane: slide it down to the lowest one, which goes below.
      Item* lowest = std::min_element(items + begin, items + end,
                                      [&](const Item& a, const Item& b) { return a.p[axis] < b.p[axis]; });
      std::swap(*lowest, items[begin]);
      split = items[begin].p[axis];
      mid = items + begin + 1;
    } else if (mid == items + end) {
      // Every photon below: slide it up to the highest one, which goes above.
      Item* highest = std::max_element(items + begin, items + end,
                                       [&](const Item& a, const Item& b) { return a.p[axis] < b.p[axis]; });
      std::swap(*highest, items[end - 1]);
      split = items[end - 1].p[axis];
      mid = items + end - 1;
    }
    const std::uint32_t m = std::uint32_t(mid - items);
    const std::size_t self = nodes_.size();
    nodes_.emplace_back();
    accel::Aabb lower = cell, upper = cell;
    lower.hi[axis] = split;
    upper.lo[axis] = split;
    build(begin, m, lower, depth + 1);
    nodes_[self] = accel::KdNode::inner(axis, split, std::uint32_t(nodes_.size()));
    build(m, end, upper, depth + 1);
  }

  int depth() const { return stats_depth_; }
  std::uint64_t leaves() const { return leaves_; }
  std::uint64_t max_leaf() const { return max_leaf_; }

 private:
  std::uint32_t leaf_size_;
  std::vector<accel::KdNode>& nodes_;
  std::vector<Item>& order_;
  int stats_depth_ = 0;
  std::uint64_t leaves_ = 0, max_leaf_ = 0;
};

}  // namespace

BucketTree::BucketTree(std::span<const Photon> photons, int leaf_size) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::uint32_t n = std::uint32_t(photons.size());
  if (n > 0) {
    std::vector<Item> order(n);
    for (std::uint32_t i = 0; i < n; ++i) {
      const Vec3& p = photons[i].position;
      order[i] = {{p.x, p.y, p.z}, i};
      bounds_.grow(p);
    }
    nodes_.reserve(2 * (std::size_t(n) / std::size_t(std::max(1, leaf_size)) + 1));
    Builder b(std::max(1, leaf_size), nodes_, order);
    b.build(0, n, bounds_, 0);
    photons_.resize(n);
    ids_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) {
      photons_[i] = photons[order[i].id];
      photons_[i].flags = 3;
      ids_[i] = order[i].id;
    }
    stats_.depth = b.depth();
    stats_.leaves = b.leaves();
    stats_.max_leaf_photons = b.max_leaf();
  }
  stats_.photons = n;
  stats_.nodes = nodes_.size();
  stats_.memory_bytes = photons_.capacity() * sizeof(Photon) +
                        ids_.capacity() * sizeof(std::uint32_t) +
                        nodes_.capacity() * sizeof(accel::KdNode);
  stats_.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace photon
