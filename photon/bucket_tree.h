#pragma once
// A photon kd-tree with leaf buckets: inner cells split one axis at a plane, leaves hold up to
// leaf_size photons stored contiguously. Nodes are accel's 8-byte kd-tree node (the lower child
// follows its parent, the upper child's index is stored). Built by the sliding-midpoint rule
// (sliding_midpoint_builder.cpp, unbalanced) or the median rule (median_bucket_builder.cpp,
// balanced); the recursion they share is bucket_builder.h.
//
// The search keeps, per cell, the offset of the query from the cell along each axis (Arya and
// Mount's incremental distance): a far child's lower bound is the squared length of that offset
// vector with the split axis replaced by the query's distance to the plane, summed in the same
// order as distance2(), so it never exceeds the distance of a photon inside (neighbor_heap.h).

#include "photon.h"
#include "photon_tree_stats.h"

#include "accel/geometry.h"
#include "accel/kdtree.h"

#include <cstdint>
#include <span>
#include <vector>

namespace photon {

class BucketTree {
 public:
  /// Deepest level the builder makes (root = 0); a cell there is a leaf whatever it holds.
  static constexpr int kMaxDepth = 60;
  static constexpr int kStackSize = kMaxDepth + 4;

  BucketTree() = default;
  /// Builds over `photons` (original index = position in the span) with the sliding-midpoint
  /// rule and leaves of at most `leaf_size` photons (except cells of coincident photons and
  /// cells at kMaxDepth).
  static BucketTree sliding_midpoint(std::span<const Photon> photons, int leaf_size);
  /// The same with the median rule (a balanced tree).
  static BucketTree median(std::span<const Photon> photons, int leaf_size);
  /// A built tree: photons and their original indices in leaf order, nodes root first.
  BucketTree(std::vector<Photon> photons, std::vector<std::uint32_t> ids,
             std::vector<accel::KdNode> nodes, const accel::Aabb& bounds, PhotonTreeStats stats)
      : photons_(std::move(photons)), ids_(std::move(ids)), nodes_(std::move(nodes)),
        bounds_(bounds), stats_(stats) {
    stats_.photons = photons_.size();
    stats_.nodes = nodes_.size();
    stats_.memory_bytes = photons_.capacity() * sizeof(Photon) +
                          ids_.capacity() * sizeof(std::uint32_t) +
                          nodes_.capacity() * sizeof(accel::KdNode);
  }

  /// Photons in leaf order.
  std::span<const Photon> storage() const { return photons_; }
  /// Original index of the photon in each slot.
  const std::uint32_t* ids() const { return ids_.data(); }
  std::size_t size() const { return photons_.size(); }
  std::span<const accel::KdNode> nodes() const { return nodes_; }
  /// The root cell: the photons' bounding box.
  const accel::Aabb& bounds() const { return bounds_; }
  const PhotonTreeStats& stats() const { return stats_; }

  template <class State>
  void search(State& s) const {
    if (photons_.empty()) return;
    const float q[3] = {s.query().x, s.query().y, s.query().z};
    // Offsets of the query from the root cell (0 inside), then their squared length.
    float off[3];
    for (int a = 0; a < 3; ++a) {
      const float below = bounds_.lo[a] - q[a], above = q[a] - bounds_.hi[a];
      off[a] = below > 0.0f ? below : (above > 0.0f ? above : 0.0f);
    }
    if (off[0] * off[0] + off[1] * off[1] + off[2] * off[2] > s.bound2()) return;
    struct Pending {
      std::uint32_t node;
      float bound2;
      float off[3];
    };
    Pending stack[kStackSize];
    int sp = 0;
    std::uint32_t node = 0;
    const accel::KdNode* nodes = nodes_.data();
    for (;;) {
      s.count_node();
      const accel::KdNode n = nodes[node];
      if (!n.is_leaf()) {
        const int axis = n.axis();
        const float delta = q[axis] - n.split();
        const std::uint32_t lower = node + 1, upper = n.upper_child();
        Pending far{delta < 0.0f ? upper : lower, 0.0f, {off[0], off[1], off[2]}};
        far.off[axis] = delta;
        far.bound2 = far.off[0] * far.off[0] + far.off[1] * far.off[1] + far.off[2] * far.off[2];
        if (far.bound2 <= s.bound2()) stack[sp++] = far;
        node = delta < 0.0f ? lower : upper;
        continue;
      }
      for (std::uint32_t i = n.prim_begin(), end = i + n.prim_count(); i < end; ++i)
        s.consider(i);
      for (;;) {
        if (sp == 0) return;
        const Pending& e = stack[--sp];
        if (e.bound2 <= s.bound2()) {
          node = e.node;
          off[0] = e.off[0], off[1] = e.off[1], off[2] = e.off[2];
          break;
        }
      }
    }
  }

 private:
  std::vector<Photon> photons_;
  std::vector<std::uint32_t> ids_;
  std::vector<accel::KdNode> nodes_;
  accel::Aabb bounds_;
  PhotonTreeStats stats_;
};

}  // namespace photon
