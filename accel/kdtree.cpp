#include "kdtree.h"

#include "accel.h"
#include "params_json.h"

#include <chrono>
#include <climits>

namespace accel {

void to_json(nlohmann::json& j, const KdTreeParams& p) {
  j = {{"max_depth", p.max_depth},
       {"max_leaf_size", p.max_leaf_size},
       {"placement", placement_name(p.placement)},
       {"split", p.split == SplitRule::Midpoint ? "midpoint" : "sah"},
       {"traversal_cost", p.traversal_cost},
       {"intersection_cost", p.intersection_cost},
       {"empty_bonus", p.empty_bonus}};
}

void from_json(const nlohmann::json& j, KdTreeParams& p) {
  KnobReader r("kdtree", j);
  r.read("max_depth", p.max_depth, 0, 64);
  r.read("max_leaf_size", p.max_leaf_size, 1, INT_MAX);
  r.read_enum("placement", p.placement,
              {{"leaves", Placement::Leaves}, {"every_level", Placement::EveryLevel}});
  r.read_enum("split", p.split, {{"midpoint", SplitRule::Midpoint}, {"sah", SplitRule::Sah}});
  r.read("traversal_cost", p.traversal_cost, 0.0f, 1e6f);
  r.read("intersection_cost", p.intersection_cost, 1e-6f, 1e6f);
  r.read("empty_bonus", p.empty_bonus, 0.0f, 1.0f);
  r.finish();
}

void validate(const KdTreeParams& p) {
  // Route the struct through the JSON reader so both paths give the same one-line messages.
  KdTreeParams checked;
  from_json(nlohmann::json(p), checked);
}

KdTree::KdTree(std::span<const Aabb> boxes, const KdTreeParams& params, const BuildLimits& limits)
    : params_(params) {
  validate(params_);
  const auto start = std::chrono::steady_clock::now();
  build(boxes, memory_budget_bytes(limits));
  stats_.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

KdTree::KdTree(std::span<const Aabb> boxes, const KdTreeParams& params)
    : KdTree(boxes, params, BuildLimits{}) {}

}  // namespace accel
