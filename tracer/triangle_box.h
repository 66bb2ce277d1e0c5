#pragma once
// Whether a triangle touches an axis-aligned box: the separating-axis test of Akenine-Moller
// (2001), in double, against the box widened by a small margin so that the answer is conservative.
// Also the box of a triangle's part inside a box (clipping), for the SAH kd-tree's split
// candidates. The octree and the kd-trees ask them (accel/primitive_overlap.h) so that a cell holds only the
// triangles that can be hit inside it.

#include "scene_geometry.h"

#include "accel/primitive_overlap.h"

namespace tracer {

/// True unless a separating axis shows the triangle misses `cell` widened by `margin` on every
/// side (world units).
bool triangle_touches_box(const Triangle& tri, const accel::Aabb& cell, double margin);

/// The box around the part of the triangle inside `cell` widened by `margin`, itself widened by
/// `margin` (Sutherland-Hodgman in double); false when that part is empty.
bool clip_triangle_to_box(const Triangle& tri, const accel::Aabb& cell, double margin, accel::Aabb& part);

/// The overlap test of `geometry`'s primitives for the trees that divide space: triangles by
/// triangle_touches_box with a margin of 2^-16 of the cell's size and distance from the origin
/// (well above the traversal's slack), every other kind by its box; and the clip for the SAH
/// kd-tree's candidates, triangles by clip_triangle_to_box with the same margin. Valid while
/// `geometry` lives.
accel::PrimitiveOverlap primitive_overlap(const Geometry& geometry);

}  // namespace tracer
