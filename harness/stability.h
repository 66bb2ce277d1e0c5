#pragma once
// The stability suite: a scene and its variants at the extremes (harness/stability_variants.h),
// rendered by naive in float and in double and through every structure, compared with the base
// render, with the double reference, and structure against naive.

#include "harness/stability_variants.h"

#include "tracer/render.h"
#include "tracer/scene.h"

#include <nlohmann/json.hpp>

#include <ostream>
#include <string>
#include <vector>

namespace harness {

/// One structure to check against naive: a factory name and its knobs.
struct CheckedStructure {
  std::string label;       ///< As written: "kdtree", "kdtree:split=sah".
  std::string name;        ///< Factory name.
  nlohmann::json params;   ///< Its knobs (an object).
};

/// The structures of `list`: comma-separated entries NAME or NAME:KNOB=VALUE[:KNOB=VALUE...]
/// (a VALUE that parses as a number is a number). Throws std::runtime_error naming `flag` for
/// an unknown or unbuilt structure; knobs are checked when the structure is built.
std::vector<CheckedStructure> parse_checked_structures(const std::string& list, const std::string& flag);

/// Every built exact structure but naive, and as extra entries every other choice of its variant
/// knobs (Knob::variant(): octree:placement=every_level, kdtree:placement=every_level,
/// kdtree:split=sah).
std::string default_structures();

struct StabilityOptions {
  std::string scene_label;                 ///< Scene file, as given (recorded in the JSON).
  const tracer::Integrator* integrator = nullptr;  ///< whitted or spd (integrators/integrators.h).
  /// The integrator's knobs for every render (e.g. {"triangle": "moller"}); the suite sets
  /// `precision` itself.
  nlohmann::json integrator_params = nlohmann::json::object();
  std::vector<CheckedStructure> structures;   ///< Checked against naive on every variant.
  std::vector<StabilityVariant> variants;  ///< Base first.
  int width = 96;                          ///< Image width, pixels.
  int height = 72;                         ///< Image height, pixels.
  int threads = 0;                         ///< Render threads; 0 = every core.
  bool reference = true;                   ///< Also render every variant in double (naive).
  std::string images_dir;                  ///< Where PNGs of every render go; "" = none.
};

/// The suite's thresholds for a variant: a secondary ray count (reflection, refraction,
/// shadow) may change by at most `max_ray_change` and at most `max_fraction_off` of the pixels
/// may be more than 1% off the base (negative: no bound). Null for variants without a target.
nlohmann::json variant_target(const StabilityVariant& v);

/// Runs the suite on `scene`; progress lines go to `progress`. Returns the results document
/// (results/schema/stability.schema.json); its "failures" counts the structure disagreements
/// and the images with a NaN or infinity.
nlohmann::json run_stability(const tracer::Scene& scene, const StabilityOptions& options,
                             std::ostream& progress);

/// The results as a fixed-width text table, one row per variant.
std::string stability_table(const nlohmann::json& doc);

}  // namespace harness
