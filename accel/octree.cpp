#include "octree.h"

#include "accel.h"
#include "params_json.h"

#include <chrono>
#include <climits>
#include <string>

namespace accel {

void to_json(nlohmann::json& j, const OctreeParams& p) {
  j = {{"max_depth", p.max_depth},
       {"max_leaf_size", p.max_leaf_size},
       {"placement", placement_name(p.placement)}};
}

void from_json(const nlohmann::json& j, OctreeParams& p) {
  KnobReader r("octree", j);
  r.read("max_depth", p.max_depth, 0, 64);
  r.read("max_leaf_size", p.max_leaf_size, 1, INT_MAX);
  r.read_enum("placement", p.placement,
              {{"leaves", Placement::Leaves}, {"every_level", Placement::EveryLevel}});
  r.finish();
}

void validate(const OctreeParams& p) {
  // Route the struct through the JSON reader so both paths give the same one-line messages.
  OctreeParams checked;
  from_json(nlohmann::json(p), checked);
}

Octree::Octree(std::span<const Aabb> boxes, const OctreeParams& params, const BuildLimits& limits)
    : params_(params) {
  validate(params_);
  const auto start = std::chrono::steady_clock::now();
  build(boxes, memory_budget_bytes(limits));
  stats_.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

Octree::Octree(std::span<const Aabb> boxes, const OctreeParams& params)
    : Octree(boxes, params, BuildLimits{}) {}

}  // namespace accel
