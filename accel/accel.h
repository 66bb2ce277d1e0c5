#pragma once
// Every structure behind one name-based factory, as a std::variant visited once per render so
// that each structure's traversal loop is compiled on its own.

#include "auto_select.h"
#include "bvh.h"
#include "geometry.h"
#include "kdtree.h"
#include "naive.h"
#include "octree.h"
#include "stats.h"
#if ACCELBENCH_HAVE_EMBREE
#include "embree_accel.h"
#endif

#include <nlohmann/json.hpp>

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace accel {

/// A bad structure name, knob or resource limit; what() is one line naming the knob.
struct ConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Limits every builder honours; a build that would pass one throws ConfigError naming the knob.
struct BuildLimits {
  /// Most bytes a structure may allocate for nodes and references; 0 means 25% of physical RAM.
  std::uint64_t max_memory_bytes = 0;
};

/// Resolves 0 to the default budget of 25% of physical memory.
std::uint64_t memory_budget_bytes(const BuildLimits& limits);

using AnyAccel = std::variant<Naive, Bvh, Octree, KdTree,
#if ACCELBENCH_HAVE_EMBREE
                               EmbreeAccel,
#endif
                               AutoSelected<Naive>, AutoSelected<Bvh>>;

/// Names accepted by make_accel, in display order.
std::vector<std::string> accel_names();

/// False for a structure compiled out of this build (embree without Embree 3); make_accel then
/// throws ConfigError saying how to get it.
bool accel_built(std::string_view name);

/// Builds the structure `name` over `boxes`. `params` holds that structure's knobs (unknown keys
/// are rejected). Throws ConfigError.
AnyAccel make_accel(std::string_view name, const nlohmann::json& params,
                    std::span<const Aabb> boxes, const BuildLimits& limits = {});

/// The exact parameters a built structure used, every knob spelled out.
nlohmann::json params_of(const AnyAccel& a);
std::string name_of(const AnyAccel& a);
const BuildStats& stats_of(const AnyAccel& a);
/// stats_of as JSON, plus a "note" where a structure cannot report some fields (embree).
nlohmann::json stats_json_of(const AnyAccel& a);

}  // namespace accel
