#pragma once
// The kd-tree's SAH split search (pbrt-v3's sweep over the primitive box faces, or over the faces
// of the primitives' parts clipped to the cell), used by the kd-tree builder when the split rule
// is `sah`.

#include "build_budget.h"
#include "geometry.h"
#include "kdtree.h"
#include "primitive_overlap.h"

#include <cstdint>
#include <span>
#include <vector>

namespace accel {

/// A split plane chosen for a cell.
struct KdSplit {
  int axis = 0;          ///< Axis the plane is normal to.
  float position = 0.0f; ///< Plane coordinate on that axis.
};

/// Side flags the split search writes per primitive id: below, above, or both (straddling).
inline constexpr std::uint8_t kBelow = 1, kAbove = 2;

class KdSahSplitter {
 public:
  /// Sizes the edge arrays for `boxes` through `budget` (6 floats-and-ids per primitive, and a
  /// box per primitive when the candidates are clipped by `overlap`).
  KdSahSplitter(std::span<const Aabb> boxes, const KdTreeParams& params, const PrimitiveOverlap& overlap,
                BuildBudget& budget);

  /// The cheapest split of `cell` over `prims`, with their sides OR-ed into side[prim id]; or
  /// false when a leaf is cheaper (pbrt-v3's rule, which allows three splits on a path that
  /// cost more than the leaf they replace, counted in `bad_refines`).
  bool find(const Aabb& cell, std::span<const std::uint32_t> prims, int& bad_refines,
            KdSplit& split, std::uint8_t* side);

 private:
  /// A primitive box face on one axis: its coordinate, and prim id << 1 | 1 for an upper face.
  struct Edge {
    float t;
    std::uint32_t prim_end;
  };

  std::span<const Aabb> boxes_;
  const KdTreeParams& params_;
  const PrimitiveOverlap& overlap_;
  bool clipped_;             ///< Candidates from the parts inside the cell (parts_).
  std::vector<Aabb> parts_;  ///< Per position in `prims`: the primitive's part inside the cell.
  std::vector<Edge> edges_[3];
};

}  // namespace accel
