// Builds the balanced photon tree: each cell's photons are partitioned at the median of the
// cell's longest axis (std::nth_element), the median becomes the node, and the halves go to
// the children, sized so that the tree is left-balanced (a complete binary tree, filled left to
// right on its last level).

#include "balanced_tree.h"

#include "accel/geometry.h"

#include <algorithm>
#include <bit>
#include <chrono>

namespace photon {

namespace {

/// A photon's position and original index, what the partitioning moves (16 bytes).
struct Item {
  float p[3];
  std::uint32_t id;
};

/// Nodes in the left subtree of a left-balanced tree of n >= 1 nodes. With h = floor(log2 n),
/// levels 0..h-1 are full (2^h - 1 nodes) and the last level holds L = n - (2^h - 1) nodes,
/// filled from the left; the left subtree has the full levels 1..h-1 of its half (2^(h-1) - 1
/// nodes) and min(L, 2^(h-1)) of the last level.
std::uint32_t left_subtree_size(std::uint32_t n) {
  if (n <= 1) return 0;
  const int h = std::bit_width(n) - 1;
  const std::uint32_t half = 1u << (h - 1);
  const std::uint32_t last = n - ((1u << h) - 1);
  return half - 1 + std::min(last, half);
}

class Builder {
 public:
  Builder(std::span<const Photon> in, std::vector<Photon>& heap, std::vector<std::uint32_t>& ids)
      : in_(in), heap_(heap), ids_(ids) {}

  void build(Item* items, std::uint32_t n, std::uint32_t node, accel::Aabb cell, int depth) {
    depth_ = std::max(depth_, depth);
    if (n == 0) return;
    const std::uint32_t m = left_subtree_size(n);
    int axis = 3;  // a leaf
    if (n > 1) {
      axis = cell.longest_axis();
      std::nth_element(items, items + m, items + n,
                       [axis](const Item& a, const Item& b) { return a.p[axis] < b.p[axis]; });
    }
    const Item& median = items[m];
    Photon& p = heap_[node];
    p = in_[median.id];
    p.flags = std::uint16_t(axis);
    ids_[node] = median.id;
    if (n == 1) return;
    const float split = median.p[axis];
    accel::Aabb lower = cell, upper = cell;
    lower.hi[axis] = split;
    upper.lo[axis] = split;
    build(items, m, 2 * node, lower, depth + 1);
    build(items + m + 1, n - m - 1, 2 * node + 1, upper, depth + 1);
  }
  int depth() const { return depth_; }

 private:
  std::span<const Photon> in_;
  std::vector<Photon>& heap_;
  std::vector<std::uint32_t>& ids_;
  int depth_ = 0;
};

}  // namespace

BalancedTree::BalancedTree(std::span<const Photon> photons) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::uint32_t n = std::uint32_t(photons.size());
  if (n > 0) {
    std::vector<Item> items(n);
    accel::Aabb bounds;
    for (std::uint32_t i = 0; i < n; ++i) {
      const Vec3& p = photons[i].position;
      items[i] = {{p.x, p.y, p.z}, i};
      bounds.grow(p);
    }
    heap_.resize(std::size_t(n) + 1);
    ids_.resize(std::size_t(n) + 1);
    Builder b(photons, heap_, ids_);
    b.build(items.data(), n, 1, bounds, 1);
    stats_.depth = b.depth();
  }
  stats_.photons = n;
  stats_.nodes = n;
  stats_.leaves = n - n / 2;
  stats_.max_leaf_photons = n ? 1 : 0;
  stats_.memory_bytes = heap_.capacity() * sizeof(Photon) + ids_.capacity() * sizeof(std::uint32_t);
  stats_.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace photon
