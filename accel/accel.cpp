#include "accel.h"

#include <unistd.h>

#include <type_traits>

namespace accel {

std::uint64_t memory_budget_bytes(const BuildLimits& limits) {
  if (limits.max_memory_bytes) return limits.max_memory_bytes;
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return std::uint64_t(4) << 30;
  return std::uint64_t(pages) * std::uint64_t(page) / 4;
}

std::vector<std::string> accel_names() { return {"naive", "octree", "kdtree", "bvh", "embree", "auto"}; }

bool accel_built(std::string_view name) {
  if (name == "embree") return ACCELBENCH_HAVE_EMBREE != 0;
  for (const std::string& n : accel_names())
    if (n == name) return true;
  return false;
}

namespace {

/// Reads a structure's parameter struct from its JSON knobs (null = every default).
template <class Params>
Params parse_params(const nlohmann::json& j) {
  Params p;
  from_json(j, p);
  return p;
}

std::string valid_names() {
  std::string out;
  for (const std::string& n : accel_names()) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return out;
}

/// The knobs of one structure as JSON (an empty object for a structure without knobs).
template <class S>
nlohmann::json knobs_of(const S& s) {
  if constexpr (requires { s.params(); })
    return nlohmann::json(s.params());
  else
    return nlohmann::json::object();
}

template <class S>
struct IsAutoSelected : std::false_type {};
template <class S>
struct IsAutoSelected<AutoSelected<S>> : std::true_type {};

}  // namespace

AnyAccel make_accel(std::string_view name, const nlohmann::json& params,
                    std::span<const Aabb> boxes, const BuildLimits& limits) {
  if (!params.is_null() && !params.is_object())
    throw ConfigError(std::string(name) + ": parameters must be a JSON object, got " + params.dump());
  if (name == "naive") {
    if (!params.is_null() && !params.empty())
      throw ConfigError("naive: unknown parameter '" + params.begin().key() + "'");
    return Naive(boxes);
  }
  if (name == "bvh") return Bvh(boxes, parse_params<BvhParams>(params), limits);
  if (name == "octree") return Octree(boxes, parse_params<OctreeParams>(params), limits);
  if (name == "kdtree") return KdTree(boxes, parse_params<KdTreeParams>(params), limits);
  if (name == "embree") {
#if ACCELBENCH_HAVE_EMBREE
    return EmbreeAccel(boxes, parse_params<EmbreeParams>(params), limits);
#else
    throw ConfigError("embree: not built (Embree 3 was not found; run scripts/setup)");
#endif
  }
  if (name == "auto") {
    const auto p = parse_params<AutoParams>(params);
    if (choose_structure(p, boxes.size()) == AutoChoice::Naive)
      return AutoSelected<Naive>(Naive(boxes), p);
    return AutoSelected<Bvh>(Bvh(boxes, BvhParams{}, limits), p);
  }
  throw ConfigError("unknown structure '" + std::string(name) + "' (valid: " + valid_names() + ")");
}

nlohmann::json params_of(const AnyAccel& a) {
  return std::visit(
      [](const auto& s) -> nlohmann::json {
        nlohmann::json j = knobs_of(s);
        // A structure `auto` picked says so, with the knobs that picked it.
        if constexpr (IsAutoSelected<std::decay_t<decltype(s)>>::value)
          j["selected_by"] = {{"structure", "auto"}, {"params", s.auto_params()}};
        return j;
      },
      a);
}
std::string name_of(const AnyAccel& a) {
  return std::visit([](const auto& s) -> std::string { return std::decay_t<decltype(s)>::kName; }, a);
}
const BuildStats& stats_of(const AnyAccel& a) {
  return std::visit([](const auto& s) -> const BuildStats& { return s.stats(); }, a);
}
nlohmann::json stats_json_of(const AnyAccel& a) {
  return std::visit(
      [](const auto& s) -> nlohmann::json {
        nlohmann::json j = s.stats();
        if constexpr (requires { s.stats_note(); }) j["note"] = s.stats_note();
        return j;
      },
      a);
}

}  // namespace accel
