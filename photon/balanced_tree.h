#pragma once
// The paper's photon tree (Jensen 1996, "Global illumination using photon maps"): every photon
// is a node, each node splits its cell at the median of the cell's longest axis, and the tree is
// stored left-balanced as a heap: node i (1-based) has children 2i and 2i+1, no pointers. A
// node i is a leaf when 2i > N, and has a right child only when 2i + 1 <= N. (Jensen's published
// locate_photons treats nodes from half = N/2 - 1 on as leaves and never reaches the photons
// below them; tests/photon_knn_test.cpp compares every variant with brute force to catch that.)
// Built in balanced_tree_builder.cpp; the search is here, a template on the gather state.

#include "photon.h"
#include "photon_tree_stats.h"

#include "accel/geometry.h"

#include <cstdint>
#include <span>
#include <vector>

namespace photon {

class BalancedTree {
 public:
  /// Deepest tree the search stack supports: depth = ceil(log2(N + 1)) <= 33 for N < 2^32.
  static constexpr int kStackSize = 40;

  BalancedTree() = default;
  /// Builds over `photons` (original index = position in the span) on up to `build_threads`
  /// threads (0: one per core); the tree does not depend on the number of threads.
  explicit BalancedTree(std::span<const Photon> photons, int build_threads = 1);

  /// Photons in heap order: slot i is node i, slot 0 unused; flags hold the split axis (3: leaf).
  std::span<const Photon> storage() const { return heap_; }
  /// Original index of the photon in each slot (slot 0 unused).
  const std::uint32_t* ids() const { return ids_.data(); }
  std::size_t size() const { return heap_.empty() ? 0 : heap_.size() - 1; }
  const PhotonTreeStats& stats() const { return stats_; }
  /// The root cell: the photons' bounding box.
  const accel::Aabb& bounds() const { return bounds_; }

  /// Offers the gather state every photon that may be among the k nearest, near side first.
  /// Each pending subtree carries the query's offset from its cell along each axis (Arya and
  /// Mount's incremental distance, as in bucket_tree.h). A node's own photon lies on its split
  /// plane inside its cell, so the far child's bound is its bound too: it is offered on the way
  /// down when that bound passes. (Deferring it until the near subtree is done, when the heap's
  /// bound is tighter, measured the same: fewer heap inserts, more pushes.)
  template <class State>
  void search(State& s) const {
    const std::uint32_t n = std::uint32_t(size());
    if (n == 0) return;
    const Photon* heap = heap_.data();
    const float q[3] = {s.query().x, s.query().y, s.query().z};
    float off[3];
    for (int a = 0; a < 3; ++a) {
      const float below = bounds_.lo[a] - q[a], above = q[a] - bounds_.hi[a];
      off[a] = below > 0.0f ? below : (above > 0.0f ? above : 0.0f);
    }
    if (off[0] * off[0] + off[1] * off[1] + off[2] * off[2] > s.bound2()) return;
    struct Pending {
      std::uint32_t node;
      float bound2;  // lower bound of the squared distances in the subtree
      float off[3];
    };
    Pending stack[kStackSize];
    int sp = 0;
    std::uint32_t i = 1;
    for (;;) {
      s.count_node();
      const std::uint32_t left = 2 * i;
      if (left > n) {
        s.consider(i);  // a leaf popped from the stack
      } else {
        const Photon& p = heap[i];
        const int axis = p.flags & 3;
        const float delta = q[axis] - (&p.position.x)[axis];
        // Arithmetic, not branches: which side the query is on is a coin toss for the predictor.
        const std::uint32_t near = left + (delta >= 0.0f);
        const std::uint32_t far = left + (delta < 0.0f);
        Pending& e = stack[sp];
        e = {far, 0.0f, {off[0], off[1], off[2]}};
        e.off[axis] = delta;
        e.bound2 = e.off[0] * e.off[0] + e.off[1] * e.off[1] + e.off[2] * e.off[2];
        s.consider(i);
        if (2 * left <= n) {
          // Both children exist and at least the left one is inner: go near, keep far.
          ++sp;
          i = near;
          continue;
        }
        // The children are leaves (the right one may be missing): offer them here, which saves
        // a descent and a leaf test per leaf.
        if (near <= n) {
          s.count_node();
          s.consider(near);
        }
        if (far <= n && e.bound2 <= s.bound2()) {
          s.count_node();
          s.consider(far);
        }
      }
      for (;;) {
        if (sp == 0) return;
        const Pending& e = stack[--sp];
        if (e.bound2 > s.bound2()) continue;
        i = e.node;
        off[0] = e.off[0], off[1] = e.off[1], off[2] = e.off[2];
        break;
      }
    }
  }

 private:
  std::vector<Photon> heap_;
  std::vector<std::uint32_t> ids_;
  accel::Aabb bounds_;
  PhotonTreeStats stats_;
};

}  // namespace photon
