#pragma once
// Choosing a configuration by accuracy: `accelbench tune SCENE --max-error E` returns the fastest
// configuration whose error is at most E, `--max-time T` the most accurate one rendering within
// T milliseconds, each with its measured time and error and the front it came from. The points
// come from a fronts results file (`accelbench fronts`), given or measured first.

#include "fronts_flags.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

// CLI::App is only named here; the files that register the flags include CLI11, and the others
// (tests, the fuzz target) are spared its ~10 s of compile time per file.
namespace CLI {
class App;
}  // namespace CLI

namespace bench {

/// What the tuner chose.
struct AccuracyChoice {
  std::string scene;         ///< Scene of the choice.
  std::string front;         ///< Knob group the chosen row belongs to.
  std::string metric;        ///< The error metric ("rmse" or "rel_mse").
  nlohmann::json row;        ///< The chosen row, as measured.
  double render_ms = 0.0;    ///< Its median render time, ms.
  double error = 0.0;        ///< Its error in `metric`.
  /// The Pareto front it was chosen from (every group of the scene, or the one asked for),
  /// fastest first: key, front, integrator_params, render_ms, error.
  nlohmann::json pareto = nlohmann::json::array();
};

/// The fastest ok row of `scene` (any group, or `front` when not empty) whose error is <= max_error.
/// Throws SweepError "--max-error: ..." naming the smallest error measured when none is.
AccuracyChoice choose_within_error(const nlohmann::json& results, const std::string& scene, double max_error,
                                   const std::string& front = "");

/// The most accurate ok row of `scene` whose median render time is <= max_ms. Throws SweepError
/// "--max-time: ..." naming the fastest time measured when none is.
AccuracyChoice choose_within_time(const nlohmann::json& results, const std::string& scene, double max_ms,
                                  const std::string& front = "");

nlohmann::json to_json(const AccuracyChoice& c);

/// The accuracy flags of `accelbench tune`.
struct AccuracyTuneFlags {
  std::string max_error, max_time;  ///< --max-error E, --max-time T (ms); exactly one.
  std::string fronts_file;          ///< --fronts FILE: choose from this results file.
  std::string front;                ///< --front NAME: only this knob group.
  FrontsFlags fronts;               ///< How to measure the fronts when no file is given.
};

/// Registers --max-error, --max-time, --fronts, --front and the fronts flags tune lacks
/// (--knobs, --values, --set, --metric, --seeds, --cache, --no-cache).
void add_accuracy_tune_flags(CLI::App& cmd, AccuracyTuneFlags& flags);

/// True when --max-error or --max-time was given.
bool accuracy_tune_requested(const AccuracyTuneFlags& flags);

/// The common flags tune shares with fronts.
struct TuneCommon {
  std::string scene, accel, resolution, seed;
  int threads = 1, repetitions = 3, warmup = 1;
};

/// Runs accuracy tuning and prints the choice; returns the exit status. `json_out` (when not
/// empty) receives the choice as JSON.
int run_accuracy_tune(const AccuracyTuneFlags& flags, const TuneCommon& common, const std::string& json_out);

}  // namespace bench
