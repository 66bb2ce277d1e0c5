#pragma once
// Where a tree stores a primitive that overlaps several children: the paper's two policies,
// shared by the octree and the kd-tree.

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace accel {

enum class Placement : std::uint8_t {
  /// A primitive is referenced by every leaf it overlaps (it may be stored many times).
  Leaves,
  /// A primitive that straddles a node's split stays in that node and is stored once (the
  /// paper's fix for the duplication of `Leaves`).
  EveryLevel,
};

/// The knob spelling of a placement: "leaves" or "every_level".
inline const char* placement_name(Placement p) {
  return p == Placement::Leaves ? "leaves" : "every_level";
}

/// The placement spelled `s`, or nothing when `s` names none.
inline std::optional<Placement> parse_placement(std::string_view s) {
  if (s == "leaves") return Placement::Leaves;
  if (s == "every_level") return Placement::EveryLevel;
  return std::nullopt;
}

inline void to_json(nlohmann::json& j, Placement p) { j = placement_name(p); }

/// Throws std::invalid_argument (one line) for anything but "leaves" or "every_level".
inline void from_json(const nlohmann::json& j, Placement& p) {
  const std::optional<Placement> parsed =
      j.is_string() ? parse_placement(j.get<std::string>()) : std::nullopt;
  if (!parsed)
    throw std::invalid_argument("placement must be \"leaves\" or \"every_level\", got " + j.dump());
  p = *parsed;
}

}  // namespace accel
