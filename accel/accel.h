#pragma once
// Every structure behind one name-based factory, as a std::variant visited once per render so
// that each structure's traversal loop is compiled on its own. The names and the variant come
// from the registry (registry.h).

#include "build_limits.h"
#include "knobs/config_error.h"
#include "geometry.h"
#include "registry.h"
#include "stats.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace accel {

/// A built structure: one alternative of StructureVariant (std::visit it), plus how it was
/// chosen when a selector such as `auto` chose it.
class AnyAccel : public StructureVariant {
 public:
  using StructureVariant::StructureVariant;
  using StructureVariant::operator=;
  AnyAccel() = default;

  /// {"structure": "auto", "params": {...}} when a selector picked this structure; else null.
  nlohmann::json selected_by;

  /// The variant itself (for std::visit on compilers that do not visit derived classes).
  const StructureVariant& variant() const { return *this; }
};

/// One registry entry as data.
struct StructureInfo {
  std::string name;               ///< Factory name.
  std::string summary;            ///< One line: what it is.
  bool built = true;              ///< False when compiled out of this build (see missing).
  std::string missing;            ///< Why it is not built and how to get it; "" when built.
  bool selector = false;          ///< Chooses among the structures (auto) instead of being one.
  /// Its hits equal naive's bit for bit (our primitive routine); false for a peer whose own
  /// primitive routine answers (embree_points), checked within a tolerance instead.
  bool exact = true;
  /// A peer we measure against (Embree), not one of ours: benchmarks pair our renders with it.
  bool peer = false;
  /// The primitives a peer tests with its own routine ("spheres", "triangles"), only in a scene
  /// of those alone; "" when our routine tests every primitive. Benchmarks time a native peer
  /// only on the scenes it is native on.
  std::string native_shapes;
  std::vector<std::string> knobs; ///< Knob names in display order.
  nlohmann::json knob_table;      ///< knobs::KnobTable::describe() of its parameter struct.
  std::string knob_markdown;      ///< knobs::KnobTable::markdown() of its parameter struct.
};

/// Every registry entry, in display order.
const std::vector<StructureInfo>& structures();
/// The entry called `name`, or null.
const StructureInfo* find_structure(std::string_view name);

/// Names accepted by make_accel, in display order.
std::vector<std::string> accel_names();

/// False for a structure compiled out of this build (embree without Embree 3) or an unknown
/// name; make_accel then throws knobs::ConfigError saying why.
bool accel_built(std::string_view name);

/// The knob names of structure `name` (empty for none); nullopt for an unknown name.
std::optional<std::vector<std::string>> knob_names(std::string_view name);

/// Throws the knobs::ConfigError make_accel would throw for knob `knob` = `value` of structure `name`
/// (unknown structure, unknown knob, wrong type, out of range); returns when it is acceptable.
void check_knob(std::string_view name, const std::string& knob, const nlohmann::json& value);

/// Throws the knobs::ConfigError make_accel would throw when structure `name` has no knob `knob`
/// ("<name>: unknown knob '<knob>' (its knobs: ...)"), or for an unknown structure.
void check_knob_name(std::string_view name, const std::string& knob);

/// Builds the structure `name` over `boxes`. `params` holds that structure's knobs (unknown keys
/// are rejected). Throws knobs::ConfigError.
AnyAccel make_accel(std::string_view name, const nlohmann::json& params,
                    std::span<const Aabb> boxes, const BuildLimits& limits = {});

/// Hands a sphere-only scene's spheres (spheres[i] is primitive i) to the built structure when
/// its leaves can test spheres in SIMD (bvh4, bvh8); other structures ignore them. The time
/// is added to the structure's build_ms.
void attach_spheres(AnyAccel& a, std::span<const SphereShape> spheres);
/// Hands a triangle-only scene's triangles (triangles[i] is primitive i) to the built structure
/// when it tests them itself (embree_triangles); other structures ignore them.
void attach_triangles(AnyAccel& a, std::span<const TriangleShape> triangles);
/// True when `a` tests triangles itself once they are attached (attach_triangles does something).
bool takes_triangles(const AnyAccel& a);

/// The exact parameters a built structure used, every knob spelled out, plus "selected_by"
/// when a selector chose it.
nlohmann::json params_of(const AnyAccel& a);
std::string name_of(const AnyAccel& a);
const BuildStats& stats_of(const AnyAccel& a);
/// stats_of as JSON, plus a "note" where a structure cannot report some fields (embree).
nlohmann::json stats_json_of(const AnyAccel& a);

/// The registry as JSON: per entry its name, summary, selector flag and knob table; the same in
/// every build (what `accelbench structures --json` prints and scripts/plot.py reads).
nlohmann::json registry_json();

/// The knob reference of every entry as Markdown (generated into docs/structures.md).
std::string knob_reference_markdown();

}  // namespace accel
