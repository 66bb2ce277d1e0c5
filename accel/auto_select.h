#pragma once
// The `auto` entry of the registry: not a structure of its own but a cost model that picks one
// of the others for the scene at hand, so that a handful of primitives is not slowed down by a
// tree (the paper's Figure 3).

#include "build_limits.h"
#include "geometry.h"
#include "knobs/knob_table.h"

#include <cstddef>
#include <span>

namespace accel {

class AnyAccel;

/// Knobs of the `auto` selection.
///
/// The cost model: naive pays one primitive test per primitive per ray and nothing else; a bvh
/// pays a per-ray setup, box tests and a stack, and wins only once the primitives it skips
/// outweigh that. The measured crossover lies between 4 and 8 primitives, later for scenes that
/// fill the view, so naive is kept up to 8. Above it `bvh8`, the fastest or near it on every
/// whole render measured. The measurements: docs/structures.md ("auto").
struct AutoParams {
  /// Scenes with at most this many primitives use naive; larger ones a bvh8 with default knobs.
  int naive_max_prims = 8;

  /// Name, range, unit and doc line of every knob above.
  static const knobs::KnobTable<AutoParams>& knobs();
};

/// What `auto` picked.
enum class AutoChoice { Naive, Tree };  // Tree: a bvh8

/// The cost model: naive while the primitive count is at most naive_max_prims, else bvh8.
AutoChoice choose_structure(const AutoParams& params, std::size_t primitives);

/// The registry entry `auto`: builds the structure the cost model picks. The result is that
/// structure itself (same name, knobs and traversal); AnyAccel::selected_by records the `auto`
/// knobs that picked it, so results rows say how it was chosen.
struct AutoSelect {
  using Params = AutoParams;
  static constexpr const char* kName = "auto";
  static constexpr const char* kSummary =
      "picks a structure for the scene with a measured cost model (naive for a few primitives)";
  /// Marks a registry entry that chooses among the structures instead of being one.
  static constexpr bool kSelector = true;

  /// Builds the structure chosen for `boxes`; throws knobs::ConfigError like make_accel.
  static AnyAccel select(std::span<const Aabb> boxes, const AutoParams& params, const BuildLimits& limits);
};

}  // namespace accel
