#include "accel.h"

#include <unistd.h>

namespace accel {

std::uint64_t memory_budget_bytes(const BuildLimits& limits) {
  if (limits.max_memory_bytes) return limits.max_memory_bytes;
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return std::uint64_t(4) << 30;
  return std::uint64_t(pages) * std::uint64_t(page) / 4;
}

std::vector<std::string> accel_names() { return {"naive"}; }

AnyAccel make_accel(std::string_view name, const nlohmann::json& params,
                    std::span<const Aabb> boxes, const BuildLimits&) {
  if (!params.is_null() && !params.is_object()) throw ConfigError("accel parameters must be an object");
  if (name == "naive") {
    if (!params.is_null() && !params.empty())
      throw ConfigError("naive: unknown parameter '" + params.begin().key() + "'");
    return Naive(boxes);
  }
  throw ConfigError("unknown structure '" + std::string(name) + "'");
}

nlohmann::json params_of(const AnyAccel& a) {
  return std::visit([](const auto&) -> nlohmann::json { return nlohmann::json::object(); }, a);
}
std::string name_of(const AnyAccel& a) {
  return std::visit([](const auto& s) -> std::string { return std::decay_t<decltype(s)>::kName; }, a);
}
const BuildStats& stats_of(const AnyAccel& a) {
  return std::visit([](const auto& s) -> const BuildStats& { return s.stats(); }, a);
}

}  // namespace accel
