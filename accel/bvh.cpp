#include "bvh.h"

#include "accel.h"
#include "params_json.h"

namespace accel {

void to_json(nlohmann::json& j, const BvhParams& p) {
  j = {{"bins", p.bins},
       {"max_leaf_size", p.max_leaf_size},
       {"max_depth", p.max_depth},
       {"traversal_cost", p.traversal_cost}};
}

void from_json(const nlohmann::json& j, BvhParams& p) {
  KnobReader r("bvh", j);
  r.read("bins", p.bins, 8, 256);
  r.read("max_leaf_size", p.max_leaf_size, 1, 255);
  r.read("max_depth", p.max_depth, 0, 64);
  r.read("traversal_cost", p.traversal_cost, 0.0f, 1000.0f);
  r.finish();
}

Bvh::Bvh(std::span<const Aabb> boxes, const BvhParams& params, const BuildLimits& limits)
    : params_(params) {
  build(boxes, memory_budget_bytes(limits));
}

Bvh::Bvh(std::span<const Aabb> boxes, const BvhParams& params) : Bvh(boxes, params, BuildLimits{}) {}

}  // namespace accel
