#include "bvh.h"

#include "accel.h"
#include "build_threads.h"

namespace accel {

const knobs::KnobTable<BvhParams>& BvhParams::knobs() {
  using K = knobs::Knob<BvhParams>;
  static const knobs::KnobTable<BvhParams> table(
      "bvh",
      {K::integer("bins", &BvhParams::bins, 8, 256, "bins per axis",
                  "Centroid bins per axis the SAH evaluates; more bins approach a full sweep.")
           .probes({8, 256}),
       K::integer("max_leaf_size", &BvhParams::max_leaf_size, 1, 255, "primitives",
                  "A node holding more primitives is always split; at or below it the SAH decides.")
           .shorthand("--leaf-size")
           .crossed()
           .probes({1, 2, 4, 8, 16}),
       K::integer("max_depth", &BvhParams::max_depth, 0, 64, "levels",
                  "Deepest level (root = 0): a node there is a leaf whatever it holds.")
           .shorthand()
           .crossed()
           .probes({0, 1, 2, 3, 5, 8, 12, 20}),
       K::number("traversal_cost", &BvhParams::traversal_cost, 0.0, 1000.0, "primitive tests",
                 "Cost of one traversal step relative to one primitive test (SAH C_trav / C_isect).")
           .probes({0.1, 1000.0}),
       K::integer(kBuildThreadsKnob, &BvhParams::build_threads, 0, 1024, "threads",
                  "Threads the build may use (0 = every core); the tree is the same at any count.")
           .probes({2}),
       K::number("spatial_split_budget", &BvhParams::spatial_split_budget, 0.0, 4.0, "references per primitive",
                 "Extra references spatial splits (SBVH) may add per primitive; 0: none. Builds on one thread.")
           .probes({0.25, 4.0})});
  return table;
}

Bvh::Bvh(std::span<const Aabb> boxes, const BvhParams& params, const BuildLimits& limits)
    : params_(params) {
  build(boxes, memory_budget_bytes(limits), limits.overlap);
}

Bvh::Bvh(std::span<const Aabb> boxes, const BvhParams& params) : Bvh(boxes, params, BuildLimits{}) {}

}  // namespace accel
