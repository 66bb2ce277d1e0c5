#include "octree.h"

#include "accel.h"

#include <chrono>
#include <climits>

namespace accel {

const knobs::KnobTable<OctreeParams>& OctreeParams::knobs() {
  using K = knobs::Knob<OctreeParams>;
  static const knobs::KnobTable<OctreeParams> table(
      "octree",
      {K::integer("max_depth", &OctreeParams::max_depth, 0, 64, "levels",
                  "Deepest level a cell may be split to (root = 0); a cell there is a leaf.")
           .shorthand()
           .crossed()
           .probes({0, 1, 2, 3, 5, 8, 12, 20}),
       K::integer("max_leaf_size", &OctreeParams::max_leaf_size, 1, INT_MAX, "primitives",
                  "A cell holding more primitives than this is split (unless max_depth stops it).")
           .shorthand("--leaf-size")
           .crossed()
           .probes({1, 2, 4, 8, 16}),
       placement_knob(&OctreeParams::placement).crossed()});
  return table;
}

Octree::Octree(std::span<const Aabb> boxes, const OctreeParams& params, const BuildLimits& limits)
    : params_(params) {
  OctreeParams::knobs().validate(params_);
  const auto start = std::chrono::steady_clock::now();
  build(boxes, memory_budget_bytes(limits), limits.overlap);
  stats_.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

Octree::Octree(std::span<const Aabb> boxes, const OctreeParams& params)
    : Octree(boxes, params, BuildLimits{}) {}

}  // namespace accel
