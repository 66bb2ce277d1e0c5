#pragma once
// Writing a wide node's child slots, shared by the direct builder (wide_bvh_builder.cpp) and the
// spatial-split collapse (wide_bvh_spatial.cpp).

#include "wide_bvh.h"

#include "accel/build_tasks.h"
#include "accel/interval_slack.h"

#include <algorithm>
#include <cstdint>

namespace accel {

/// The child a node opens next while it has fewer than W: the one of largest surface area
/// among those that are not leaves (`area`, `leaf`); -1 when every child is a leaf. The rule that
/// collapses a binary SAH tree into a wide one, for both builders.
template <class Kid>
int widest_inner_child(const Kid* kids, int k) {
  int widest = -1;
  for (int i = 0; i < k; ++i)
    if (!kids[i].leaf && (widest < 0 || kids[i].area > kids[widest].area)) widest = i;
  return widest;
}

/// Slot i of `n` unused: an empty box (+inf, -inf), which no ray enters.
template <int W>
void clear_slot(WideNode<W>& n, int i) {
  for (int a = 0; a < 3; ++a) {
    n.planes[2 * a][i] = kInfinity;
    n.planes[2 * a + 1][i] = -kInfinity;
  }
  n.child[i] = 0;
  n.count[i] = 0;
}

/// Slot i's box: `box` padded outward (box_pad), so that the float slab test never misses it.
template <int W>
void set_slot_box(WideNode<W>& n, int i, const Aabb& box) {
  for (int a = 0; a < 3; ++a) {
    const float pad = box_pad(box.lo[a], box.hi[a]);
    n.planes[2 * a][i] = box.lo[a] - pad;
    n.planes[2 * a + 1][i] = box.hi[a] + pad;
  }
}

/// Slot i a leaf over the ids [begin, end), of half-area `area`, counted in `tally`.
template <int W>
void set_leaf_slot(WideNode<W>& n, int i, std::uint32_t begin, std::uint32_t end, float area, BuildTally& tally) {
  n.child[i] = begin;
  n.count[i] = end - begin;
  tally.leaves++;
  tally.max_leaf_prims = std::max<std::uint64_t>(tally.max_leaf_prims, end - begin);
  tally.sah += double(area) * double(end - begin);
}

}  // namespace accel
