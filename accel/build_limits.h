#pragma once
// Resource limits every builder honours, and what the primitives can say beyond their boxes.

#include "primitive_overlap.h"

#include <cstdint>

namespace accel {

/// Limits every builder honours; a build that would pass one throws knobs::ConfigError naming the knob.
struct BuildLimits {
  /// Most bytes a structure may allocate for nodes and references; 0 means 25% of physical RAM.
  std::uint64_t max_memory_bytes = 0;
  /// Whether a primitive touches a cell, for the trees that divide space (octree, kd-trees);
  /// default: its box decides.
  PrimitiveOverlap overlap;
  /// The caller attaches the primitives themselves right after the build (attach_spheres or
  /// attach_triangles), so a structure that would store their boxes beside its leaves for
  /// other primitives (the wide BVHs' LeafBoxes) skips them: on a million triangles they were
  /// 24 MB written, then thrown away. Without the attach, leaves test every primitive, as after it.
  bool shapes_follow = false;
};

/// Resolves 0 to the default budget of 25% of physical memory.
std::uint64_t memory_budget_bytes(const BuildLimits& limits);

}  // namespace accel
