#include "kdtree.h"

#include "accel.h"

#include <chrono>
#include <climits>

namespace accel {

const knobs::KnobTable<KdTreeParams>& KdTreeParams::knobs() {
  using K = knobs::Knob<KdTreeParams>;
  static const knobs::KnobTable<KdTreeParams> table(
      "kdtree",
      {K::integer("max_depth", &KdTreeParams::max_depth, 0, 64, "levels",
                  "Deepest level a cell may be split to (root = 0); a cell there is a leaf.")
           .shorthand()
           .crossed()
           .probes({0, 1, 2, 3, 5, 8, 12, 20}),
       K::integer("max_leaf_size", &KdTreeParams::max_leaf_size, 1, INT_MAX, "primitives",
                  "A cell holding this many primitives or fewer is a leaf.")
           .shorthand("--leaf-size")
           .crossed()
           .probes({1, 2, 4, 8, 16}),
       placement_knob(&KdTreeParams::placement).crossed(),
       K::choice("split", &KdTreeParams::split, {{"midpoint", SplitRule::Midpoint}, {"sah", SplitRule::Sah}},
                 "How split planes are chosen: the longest axis's midpoint (the paper), or the SAH.")
           .shorthand()
           .variant()
           .crossed(),
       K::choice("split_candidates", &KdTreeParams::split_candidates,
                 {{"boxes", SplitCandidates::Boxes}, {"clipped", SplitCandidates::Clipped}},
                 "Where the SAH looks for planes: the faces of the primitives' boxes (pbrt-v3), or of "
                 "their parts clipped to the cell (triangles; Havran's perfect splits); split sah only."),
       K::number("traversal_cost", &KdTreeParams::traversal_cost, 0.0, 1e6, "SAH cost units",
                 "SAH cost of one traversal step (pbrt-v3: 1); split sah only.")
           .probes({0.0, 1e6}),
       K::number("intersection_cost", &KdTreeParams::intersection_cost, 1e-6, 1e6, "SAH cost units",
                 "SAH cost of one primitive test (pbrt-v3: 80; measured here for spheres: 0.5).")
           .probes({1e-6, 80.0}),
       K::number("empty_bonus", &KdTreeParams::empty_bonus, 0.0, 1.0, "fraction",
                 "Fraction of the SAH cost forgiven when a split leaves one side empty (pbrt-v3: 0.5).")});
  return table;
}

KdTree::KdTree(std::span<const Aabb> boxes, const KdTreeParams& params, const BuildLimits& limits)
    : params_(params) {
  KdTreeParams::knobs().validate(params_);
  const auto start = std::chrono::steady_clock::now();
  build(boxes, memory_budget_bytes(limits), limits.overlap);
  stats_.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

KdTree::KdTree(std::span<const Aabb> boxes, const KdTreeParams& params)
    : KdTree(boxes, params, BuildLimits{}) {}

}  // namespace accel
