#pragma once
// Whether a triangle touches an axis-aligned box: the separating-axis test of Akenine-Moller
// (2001), in double, against the box widened by a small margin so that the answer is conservative.
// The octree and the kd-trees ask it (accel/primitive_overlap.h) so that a cell holds only the
// triangles that can be hit inside it.

#include "scene_geometry.h"

#include "accel/primitive_overlap.h"

namespace tracer {

/// True unless a separating axis shows the triangle misses `cell` widened by `margin` on every
/// side (world units).
bool triangle_touches_box(const Triangle& tri, const accel::Aabb& cell, double margin);

/// The overlap test of `geometry`'s primitives for the trees that divide space: triangles by
/// triangle_touches_box with a margin of 2^-16 of the cell's size and distance from the origin
/// (well above the traversal's slack), every other kind by its box. Valid while `geometry` lives.
accel::PrimitiveOverlap primitive_overlap(const Geometry& geometry);

}  // namespace tracer
