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

const std::vector<StructureInfo>& structures() {
  static const std::vector<StructureInfo> table = [] {
    std::vector<StructureInfo> out;
    for_each_entry([&]<class E>() {
      StructureInfo info;
      info.name = E::kName;
      info.summary = E::kSummary;
      if constexpr (MissingEntry<E>) {
        info.built = false;
        info.missing = E::kMissing;
      }
      info.selector = SelectorEntry<E>;
      if constexpr (requires { E::kExact; }) info.exact = E::kExact;
      if constexpr (requires { E::kPeer; }) info.peer = E::kPeer;
      if constexpr (requires { E::kNativeShapes; }) info.native_shapes = E::kNativeShapes;
      const auto& knobs = E::Params::knobs();
      info.knobs = knobs.names();
      info.knob_table = knobs.describe();
      info.knob_markdown = knobs.markdown();
      out.push_back(std::move(info));
    });
    return out;
  }();
  return table;
}

const StructureInfo* find_structure(std::string_view name) {
  for (const StructureInfo& s : structures())
    if (s.name == name) return &s;
  return nullptr;
}

std::vector<std::string> accel_names() {
  std::vector<std::string> out;
  for (const StructureInfo& s : structures()) out.push_back(s.name);
  return out;
}

bool accel_built(std::string_view name) {
  const StructureInfo* s = find_structure(name);
  return s && s->built;
}

std::optional<std::vector<std::string>> knob_names(std::string_view name) {
  const StructureInfo* s = find_structure(name);
  if (!s) return std::nullopt;
  return s->knobs;
}

namespace {

std::string valid_names() {
  std::string out;
  for (const std::string& n : accel_names()) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return out;
}

}  // namespace

void check_knob(std::string_view name, const std::string& knob, const nlohmann::json& value) {
  bool found = false;
  for_each_entry([&]<class E>() {
    if (found || name != E::kName) return;
    found = true;
    typename E::Params p{};
    E::Params::knobs().read(nlohmann::json{{knob, value}}, p);
  });
  if (!found)
    throw knobs::ConfigError("unknown structure '" + std::string(name) + "' (valid: " + valid_names() + ")");
}

void check_knob_name(std::string_view name, const std::string& knob) {
  bool found = false;
  for_each_entry([&]<class E>() {
    if (found || name != E::kName) return;
    found = true;
    const auto& table = E::Params::knobs();
    if (!table.find(knob))
      throw knobs::ConfigError(std::string(E::kName) + ": unknown knob '" + knob + "' (" + table.known_text() + ")");
  });
  if (!found)
    throw knobs::ConfigError("unknown structure '" + std::string(name) + "' (valid: " + valid_names() + ")");
}

AnyAccel make_accel(std::string_view name, const nlohmann::json& params,
                    std::span<const Aabb> boxes, const BuildLimits& limits) {
  std::optional<AnyAccel> built;
  for_each_entry([&]<class E>() {
    if (built || name != E::kName) return;
    const typename E::Params p = E::Params::knobs().from_json(params);
    if constexpr (MissingEntry<E>)
      throw knobs::ConfigError(std::string(E::kName) + ": " + E::kMissing);
    else if constexpr (SelectorEntry<E>)
      built = E::select(boxes, p, limits);
    else
      built.emplace(E(boxes, p, limits));
  });
  if (!built)
    throw knobs::ConfigError("unknown structure '" + std::string(name) + "' (valid: " + valid_names() + ")");
  return std::move(*built);
}

void attach_spheres(AnyAccel& a, std::span<const SphereShape> spheres) {
  std::visit(
      [&](auto& s) {
        if constexpr (requires { s.attach_spheres(spheres); }) s.attach_spheres(spheres);
      },
      static_cast<StructureVariant&>(a));
}

void attach_triangles(AnyAccel& a, std::span<const TriangleShape> triangles) {
  std::visit(
      [&](auto& s) {
        if constexpr (requires { s.attach_triangles(triangles); }) s.attach_triangles(triangles);
      },
      static_cast<StructureVariant&>(a));
}

bool takes_triangles(const AnyAccel& a) {
  return std::visit(
      [](const auto& s) {
        // attach_triangles changes the structure, so ask of a non-const one.
        using S = std::decay_t<decltype(s)>;
        return requires(S& m, std::span<const TriangleShape> t) { m.attach_triangles(t); };
      },
      a.variant());
}

nlohmann::json params_of(const AnyAccel& a) {
  nlohmann::json j = std::visit(
      [](const auto& s) -> nlohmann::json {
        using S = std::decay_t<decltype(s)>;
        return S::Params::knobs().to_json(s.params());
      },
      a.variant());
  if (!a.selected_by.is_null()) j["selected_by"] = a.selected_by;
  return j;
}

std::string name_of(const AnyAccel& a) {
  return std::visit([](const auto& s) -> std::string { return std::decay_t<decltype(s)>::kName; }, a.variant());
}

const BuildStats& stats_of(const AnyAccel& a) {
  return std::visit([](const auto& s) -> const BuildStats& { return s.stats(); }, a.variant());
}

nlohmann::json stats_json_of(const AnyAccel& a) {
  return std::visit(
      [](const auto& s) -> nlohmann::json {
        nlohmann::json j = s.stats();
        if constexpr (requires { s.stats_note(); }) j["note"] = s.stats_note();
        return j;
      },
      a.variant());
}

nlohmann::json registry_json() {
  nlohmann::json out = nlohmann::json::array();
  for (const StructureInfo& s : structures())
    out.push_back({{"name", s.name},
                   {"summary", s.summary},
                   {"selector", s.selector},
                   {"exact", s.exact},
                   {"peer", s.peer},
                   {"native_shapes", s.native_shapes},
                   {"knobs", s.knob_table}});
  return out;
}

std::string knob_reference_markdown() {
  std::string md;
  for (const StructureInfo& s : structures()) {
    md += "### `" + s.name + "`\n\n" + s.summary + ".\n\n" + s.knob_markdown + "\n";
  }
  return md;
}

}  // namespace accel
