#include "accel.h"

#include <chrono>

namespace accel {

std::vector<std::string> accel_names() { return {"naive"}; }

AnyAccel make_accel(std::string_view name, const nlohmann::json& params,
                    std::span<const Aabb> boxes) {
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
