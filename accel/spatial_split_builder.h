#pragma once
// Spatial-split build of the binary BVH (Stich, Friedrich and Dietrich, "Spatial Splits in
// Bounding Volume Hierarchies", HPG 2009), behind the bvh's `spatial_split_budget` knob. Each
// node weighs the binned object split against a binned spatial split, which cuts the primitives
// that straddle a plane into the parts on either side (PrimitiveOverlap::part clips a triangle to
// each side). A primitive may then sit in several leaves, each holding a box around its part
// there: long or diagonal triangles stop inflating the boxes they share with their neighbours.

#include "build_tasks.h"
#include "bvh.h"
#include "primitive_overlap.h"

#include <cstdint>
#include <span>
#include <vector>

namespace accel {

/// The most references a spatial-split build over `n` primitives may make: n plus `budget`
/// (the knob spatial_split_budget) extra per primitive; n when the budget is 0.
inline std::uint64_t spatial_split_max_refs(std::uint64_t n, float budget) {
  return budget > 0.0f ? n + std::uint64_t(double(n) * double(budget)) : n;
}

/// The tree of `boxes` (primitive id = index) written into `nodes` in Bvh's layout (the root at
/// 0, an unused node at 1, sibling pairs after it, depth first) with the primitive references in
/// leaf order in `prim_ids`; at most `max_refs` references (>= boxes.size()) in all. One thread;
/// the same tree every run.
BuildTally build_spatial_split_bvh(std::span<const Aabb> boxes, const BvhParams& params,
                                   const PrimitiveOverlap& overlap, std::uint64_t max_refs,
                                   std::vector<BvhNode>& nodes, std::vector<std::uint32_t>& prim_ids);

}  // namespace accel
