#pragma once
// The structure configurations the image tests render through: every structure this build has
// at its defaults, and each structure with an `isa` knob (Embree) at every instruction set the
// CPU has, so that a test run on any machine covers every ISA that machine can run.

#include "accel/accel.h"
#include "accel/isa.h"
#include "tracer/build_accel.h"

#include <nlohmann/json.hpp>

#include <span>
#include <string>
#include <utility>
#include <vector>

namespace test_support {

/// A structure by name, with its knobs.
struct StructureConfig {
  StructureConfig(const char* structure) : name(structure) {}  // NOLINT: "bvh" reads as a config
  StructureConfig(std::string structure, nlohmann::json knobs = nlohmann::json::object())
      : name(std::move(structure)), params(std::move(knobs)) {}

  std::string name;
  nlohmann::json params;

  std::string label() const { return params.empty() ? name : name + " " + params.dump(); }
  accel::AnyAccel build(std::span<const accel::Aabb> boxes) const { return accel::make_accel(name, params, boxes); }
  /// Built as render builds it: the triangles' own cell test, the spheres attached.
  accel::AnyAccel build(const tracer::Geometry& geometry, std::span<const accel::Aabb> boxes) const {
    return tracer::build_accel(name, params, geometry, boxes);
  }
};

/// The ISA knob values a structure with an `isa` knob is rendered at: every level the CPU has.
inline std::vector<std::string> isa_values_on_this_cpu() {
  std::vector<std::string> out;
  for (accel::Isa isa : accel::isas_in(accel::cpu_isas())) out.push_back(accel::isa_name(isa));
  return out;
}

/// Every structure built here but naive whose hits equal naive's bit for bit (StructureInfo::exact),
/// at its defaults; then every such structure with an `isa` knob at each level the CPU has.
inline std::vector<StructureConfig> structures_at_every_isa() {
  std::vector<StructureConfig> out;
  for (const accel::StructureInfo& s : accel::structures()) {
    if (s.name == "naive" || !s.built || !s.exact) continue;
    out.push_back({s.name});
    for (const std::string& knob : s.knobs)
      if (knob == "isa")
        for (const std::string& isa : isa_values_on_this_cpu()) out.push_back({s.name, {{"isa", isa}}});
  }
  return out;
}

}  // namespace test_support
