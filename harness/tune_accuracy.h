#pragma once
// Choosing a configuration by accuracy: `accelbench tune SCENE --max-error E` returns the fastest
// configuration whose error is at most E, `--max-time T` the most accurate one rendering within
// T milliseconds, each with its measured time and error and the front it came from. The points
// come from a fronts results file (`accelbench fronts`), given or measured first (the flags and
// the run: cli/tune_accuracy_flags.h).

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace harness {

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

/// `x` with four significant digits ("%.4g"), as the tuner prints errors and budgets.
std::string four_significant(double x);

}  // namespace harness
