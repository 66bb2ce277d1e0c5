#pragma once
// What a tree that divides space may ask of the primitives besides their boxes: whether primitive
// `id` touches a cell. The octree and the kd-trees ask it of every primitive whose box straddles
// a split, so that a cell keeps only the primitives that can be hit inside it (a long diagonal
// triangle's box covers many cells its surface never enters). The structures know only ids and
// boxes; the tracer answers for its triangles (tracer/triangle_box.h).

#include "geometry.h"

#include <cstdint>

namespace accel {

struct PrimitiveOverlap {
  const void* context = nullptr;  ///< Passed back to `touches`.
  /// True when primitive `id` may touch the closed box `cell`; must be conservative (true
  /// whenever the exact primitive touches it). nullptr: every primitive whose box overlaps a
  /// cell touches it.
  bool (*touches)(const void* context, std::uint32_t id, const Aabb& cell) = nullptr;

  bool active() const { return touches != nullptr; }
  bool operator()(std::uint32_t id, const Aabb& cell) const { return !touches || touches(context, id, cell); }
};

}  // namespace accel
