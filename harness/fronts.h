#pragma once
// Speed/accuracy fronts (`accelbench fronts`): a sweep over an integrator's accuracy knobs in
// which every configuration is also compared with an independent reference (error metrics, and a
// bias/variance split over seeds), and whose results mark the Pareto front of time against error
// per scene and knob group. Built on the sweep machinery: definition, JSON Lines rows, resume,
// shards, validation against naive and timing are the sweep's (docs/accuracy.md).

#include "harness/accuracy_reference.h"
#include "harness/front_metric.h"
#include "harness/sweep_definition.h"
#include "harness/sweep_measure.h"
#include "harness/sweep_runner.h"

#include <nlohmann/json.hpp>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace harness {

/// What fronts add to a sweep definition (kept in SweepDefinition::fronts).
struct FrontsSettings {
  /// The knob groups, each a list of knob names varied together (one knob: one-at-a-time).
  std::vector<std::vector<std::string>> groups;
  /// Knobs held at one value in every render, the references' included (an object).
  nlohmann::json fixed = nlohmann::json::object();
  /// Knobs of the references' integrator set over their recipe (an object; --reference-set):
  /// a cheaper or stronger reference than the table's. Part of every reference's cache key.
  nlohmann::json reference = nlohmann::json::object();
  FrontMetric metric = FrontMetric::Rmse;  ///< Metric of the front and of tune.
  double epsilon = tracer::kRelMseEpsilon;  ///< Epsilon of the relative MSE.
  /// How a progressive reference (ppm) combines its stages: plain, or Richardson extrapolation
  /// (harness/reference_floor.h). Part of every such reference's cache key.
  ReferenceEstimator estimator = ReferenceEstimator::Plain;
  /// Renders per configuration with independent seeds for the bias/variance split (the timed
  /// image is the first), for groups whose reference is stochastic; 1 = no split.
  int seeds = 4;
};

nlohmann::json to_json(const FrontsSettings& s);

/// Reads SweepDefinition::fronts; throws SweepError naming the key.
FrontsSettings fronts_settings_from_json(const nlohmann::json& j);

/// A group's name: its knobs joined by '*' ("max_depth", "max_depth*spp").
std::string group_name(const std::vector<std::string>& knobs);

/// The reference recipe of a knob group of `integrator` (accuracy_knobs.h), with the fixed knobs
/// and then `overrides` (knobs of the reference integrator) on top, at width x height. Throws
/// SweepError when a knob has no row, the knobs' references disagree, or an override names a knob
/// the reference integrator does not have. A progressive reference integrator (ppm) estimates
/// its bias from its own stages with `estimator`.
ReferenceSpec group_reference(const std::string& integrator, const std::vector<std::string>& group,
                              const nlohmann::json& fixed, int width, int height,
                              const nlohmann::json& overrides = nlohmann::json::object(),
                              ReferenceEstimator estimator = ReferenceEstimator::Plain);

/// A fronts run as the command line asks for it.
struct FrontsRequest {
  std::string name = "fronts";            ///< Sweep name (file-name safe).
  std::vector<SceneSpec> scenes;          ///< Scenes, each with its own fronts.
  std::string integrator = "whitted";     ///< Integrator whose knobs are studied.
  std::string structure = "bvh";          ///< Structure every render goes through.
  /// Knob groups (see FrontsSettings::groups).
  std::vector<std::vector<std::string>> groups;
  /// Values per knob; a knob not listed takes its row's default values.
  std::map<std::string, std::vector<nlohmann::json>> values;
  FrontsSettings settings;                ///< Fixed knobs, metric, epsilon, seeds (groups filled in).
  int width = 160, height = 120;          ///< Timed resolution, pixels.
  int validate_width = 40, validate_height = 30;  ///< Check against naive; 0 = at the timed one.
  int threads = 1;                        ///< Render threads of the timed renders.
  int repetitions = 3;                    ///< Timed renders per configuration.
  int warmup = 1;                         ///< Untimed renders before them.
};

/// The sweep definition of a fronts request: one structure, the integrator's knob groups with
/// their values (fixed knobs added to every group), and the fronts settings. Throws SweepError
/// with one line naming the flag: an unknown knob, an empty range, a bad value, a knob both
/// varied and fixed.
SweepDefinition fronts_definition(const FrontsRequest& request);

/// Measures each configuration's error against its group's reference (made or read from the
/// cache on first use). Given to the sweep as its inspector.
class FrontsInspector {
 public:
  FrontsInspector(const SweepDefinition& definition, ReferenceOptions options);
  void operator()(const tracer::Scene& scene, const accel::AnyAccel& built, const MeasureOptions& mo,
                  const tracer::Image& image, Measurement& m);

  double reference_s() const { return reference_s_; }    ///< Wall time making references, s.
  int references_made() const { return made_; }          ///< References rendered now.
  int references_cached() const { return cached_; }      ///< References read from the cache.
  double error_s() const { return error_s_; }            ///< Wall time computing errors, s.

 private:
  const AccuracyReference& reference(const tracer::Scene& scene, const accel::AnyAccel& built,
                                     const std::vector<std::string>& group);
  std::string integrator_;
  FrontsSettings settings_;
  ReferenceOptions options_;
  int width_ = 0, height_ = 0;
  bool has_seed_ = false;
  std::map<std::string, AccuracyReference> references_;  // by cache key
  double reference_s_ = 0.0, error_s_ = 0.0;
  int made_ = 0, cached_ = 0;
};

/// Marks the fronts in a results document of a fronts sweep: for every scene and group, the ok
/// rows' (median render time, error) points, their Pareto front (rows get "on_front"), the
/// reference's floor and the ratio of the smallest non-zero error to it, in results["fronts"].
/// Every row gets its error's interval and whether the reference resolves it
/// (harness/error_interval.h: "error_interval", "resolved"), every front the count of its
/// unresolved points ("unresolved"); unresolved points dominate only unresolved points.
void annotate_fronts(nlohmann::json& results);

/// What a fronts run did.
struct FrontsSummary {
  RunSummary sweep;          ///< The sweep's own summary.
  double wall_s = 0.0;       ///< Whole run, references and annotation included, s.
  double reference_s = 0.0;  ///< Making (or reading) references, s.
  int references_made = 0;   ///< Rendered now.
  int references_cached = 0; ///< Read from the cache.
  /// Time outside builds and renders (references included as renders), as a fraction of the
  /// time inside them: what fronts adds over the renders it runs.
  double overhead_fraction = 0.0;
};

/// Runs a fronts sweep and writes its annotated results file (options.out_path).
FrontsSummary run_fronts(const SweepDefinition& definition, RunOptions options,
                         const ReferenceOptions& reference_options);

}  // namespace harness
