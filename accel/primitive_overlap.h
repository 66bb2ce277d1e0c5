#pragma once
// What a tree that divides space may ask of the primitives besides their boxes: whether primitive
// `id` touches a cell, and a box around its part inside a cell. The octree and the kd-trees ask
// the first of every primitive whose box straddles a split, so that a cell keeps only the
// primitives that can be hit inside it (a long diagonal triangle's box covers many cells its
// surface never enters). The SAH kd-tree asks the second for its split candidates: the faces of
// the clipped boxes are where a triangle's surface really starts and ends in the cell (Havran's
// "perfect splits"). The structures know only ids and boxes; the tracer answers for its triangles
// (tracer/triangle_box.h).

#include "geometry.h"

#include <cstdint>

namespace accel {

struct PrimitiveOverlap {
  const void* context = nullptr;  ///< Passed back to `touches` and `clip`.
  /// True when primitive `id` may touch the closed box `cell`; must be conservative (true
  /// whenever the exact primitive touches it). nullptr: every primitive whose box overlaps a
  /// cell touches it.
  bool (*touches)(const void* context, std::uint32_t id, const Aabb& cell) = nullptr;
  /// A box around the part of primitive `id` inside `cell`, within box(id) ∩ cell; conservative
  /// like `touches`. nullptr: box(id) ∩ cell.
  Aabb (*clip)(const void* context, std::uint32_t id, const Aabb& box, const Aabb& cell) = nullptr;

  bool active() const { return touches != nullptr; }
  bool operator()(std::uint32_t id, const Aabb& cell) const { return !touches || touches(context, id, cell); }
  /// The part of primitive `id`, whose box is `box`, inside `cell`.
  Aabb part(std::uint32_t id, const Aabb& box, const Aabb& cell) const {
    return clip ? clip(context, id, box, cell) : Aabb{glm::max(box.lo, cell.lo), glm::min(box.hi, cell.hi)};
  }
};

}  // namespace accel
