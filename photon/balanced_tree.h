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

#include <cstdint>
#include <span>
#include <vector>

namespace photon {

class BalancedTree {
 public:
  /// Deepest tree the search stack supports: depth = ceil(log2(N + 1)) <= 33 for N < 2^32.
  static constexpr int kStackSize = 40;

  BalancedTree() = default;
  /// Builds over `photons` (original index = position in the span).
  explicit BalancedTree(std::span<const Photon> photons);

  /// Photons in heap order: slot i is node i, slot 0 unused; flags hold the split axis (3: leaf).
  std::span<const Photon> storage() const { return heap_; }
  /// Original index of the photon in each slot (slot 0 unused).
  const std::uint32_t* ids() const { return ids_.data(); }
  std::size_t size() const { return heap_.empty() ? 0 : heap_.size() - 1; }
  const PhotonTreeStats& stats() const { return stats_; }

  /// Offers the gather state every photon that may be among the k nearest, near side first;
  /// skips a child only when its split-plane distance squared exceeds the state's bound.
  template <class State>
  void search(State& s) const {
    const std::uint32_t n = std::uint32_t(size());
    if (n == 0) return;
    const Photon* heap = heap_.data();
    const float q[3] = {s.query().x, s.query().y, s.query().z};
    struct Pending {
      std::uint32_t node;
      float d2;  // squared distance from the query to the node's split plane
    };
    Pending stack[kStackSize];
    int sp = 0;
    std::uint32_t i = 1;
    for (;;) {
      // Descend towards the query, offering each node's photon and remembering far children.
      for (;;) {
        s.count_node();
        s.consider(i);
        const std::uint32_t left = 2 * i;
        if (left > n) break;
        const Photon& p = heap[i];
        const int axis = p.flags & 3;
        const float delta = q[axis] - (&p.position.x)[axis];
        const std::uint32_t near = delta < 0.0f ? left : left + 1;
        const std::uint32_t far = delta < 0.0f ? left + 1 : left;
        const float d2 = delta * delta;
        if (far <= n && d2 <= s.bound2()) stack[sp++] = {far, d2};
        if (near > n) break;
        i = near;
      }
      for (;;) {
        if (sp == 0) return;
        const Pending e = stack[--sp];
        if (e.d2 <= s.bound2()) {
          i = e.node;
          break;
        }
      }
    }
  }

 private:
  std::vector<Photon> heap_;
  std::vector<std::uint32_t> ids_;
  PhotonTreeStats stats_;
};

}  // namespace photon
