#pragma once
// The `auto` structure: a cheap cost model picks naive or bvh for the scene at hand, so that a
// handful of primitives is not slowed down by a tree (the paper's Figure 3).

#include "bvh.h"
#include "naive.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <utility>

namespace accel {

/// Knobs of the `auto` selection.
///
/// The cost model: naive pays one primitive test per primitive per ray and nothing else; a bvh
/// pays a per-ray setup, box tests and a stack, and wins only once the primitives it skips
/// outweigh that. Measured (Release, one thread, closest hits stored per ray, bvh / naive rays
/// per second): on `random` scenes at 512x384, where many rays miss, 0.61 at 2 spheres, 0.94 at
/// 4, 1.47 at 8, 2.2 at 16, 5.4 at 64; on `five` (5 spheres filling the view) at 1024x768, 0.70.
/// The crossover lies between 4 and 8 primitives and later for scenes that fill the view, so
/// naive is kept up to 8.
struct AutoParams {
  /// Scenes with at most this many primitives use naive; larger ones a bvh with default knobs.
  int naive_max_prims = 8;
};

void to_json(nlohmann::json& j, const AutoParams& p);
/// Reads the knobs; unknown keys, wrong types and out-of-range values throw ConfigError.
void from_json(const nlohmann::json& j, AutoParams& p);

/// What `auto` picked.
enum class AutoChoice { Naive, Bvh };

/// The cost model: naive while the primitive count is at most naive_max_prims, else bvh.
AutoChoice choose_structure(const AutoParams& params, std::size_t primitives);

/// A structure that `auto` chose: the structure itself (same name, knobs and traversal), plus
/// the `auto` knobs that chose it, so results rows say how it was picked.
template <class Structure>
class AutoSelected : public Structure {
 public:
  AutoSelected() = default;
  AutoSelected(Structure chosen, const AutoParams& params)
      : Structure(std::move(chosen)), auto_params_(params) {}

  /// The knobs of the `auto` selection that picked this structure.
  const AutoParams& auto_params() const { return auto_params_; }

 private:
  AutoParams auto_params_;
};

}  // namespace accel
