#pragma once
// The flags of a fronts run, shared by `accelbench fronts` and `accelbench tune --max-error /
// --max-time` (which measures fronts first when not given a results file).

#include "harness/accuracy_reference.h"
#include "harness/fronts.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>
#include <vector>

// CLI::App is only named here; the files that register the flags include CLI11, and the others
// (tests, the fuzz target) are spared its ~10 s of compile time per file.
namespace CLI {
class App;
}  // namespace CLI

namespace cli {

using namespace harness;  // the command line drives the harness


struct FrontsFlags {
  std::vector<std::string> scenes;       ///< SCENE arguments.
  std::string knobs;                     ///< --knobs: "a,b" one at a time, "a*b" jointly.
  bool joint = false;                    ///< --joint: every listed knob in one group.
  std::vector<std::string> values;       ///< --values KNOB=v1,v2,... or KNOB=lo:hi:n.
  std::vector<std::string> set;          ///< --set KNOB=VALUE.
  std::vector<std::string> reference_set;  ///< --reference-set KNOB=VALUE.
  std::string integrator = "whitted", accel = "bvh", resolution = "160x120";
  std::string validate_resolution = "40x30", metric = "rmse", name, cache, seed = "1";
  double epsilon = tracer::kRelMseEpsilon;
  int seeds = 4, threads = 1, repetitions = 3, warmup = 1, reference_threads = 0;
  bool no_cache = false, refresh = false;
  std::string estimator = "plain";       ///< --estimator: how a progressive reference combines stages.
  double floor_target = 0.0;             ///< --floor-target: stopping rule's floor (0: none).
  std::string floor_target_from;         ///< --floor-target-from: results file whose fronts set it.
  double floor_ratio = 10.0;             ///< --floor-ratio: target = smallest error there / this.
  double reference_time_limit = 3600.0;  ///< --reference-time-limit, s.
};

/// Registers the fronts flags on `cmd` (SCENE positional arguments included).
void add_fronts_flags(CLI::App& cmd, FrontsFlags& flags);

/// The request the flags describe; throws SweepError naming the flag.
FrontsRequest request_from_flags(const FrontsFlags& flags);

/// Where and how references are made and cached, with their stopping rule (--floor-target, or
/// --floor-target-from FILE: the smallest error on that file's fronts over --floor-ratio).
/// Throws SweepError naming the flag.
ReferenceOptions reference_options_from_flags(const FrontsFlags& flags);

/// Parses a --values list: "v1,v2,..." (numbers, true/false, or words), or "lo:hi:n", n values
/// spaced evenly in log between lo > 0 and hi (integers when lo and hi are, repeats dropped).
/// Throws SweepError naming `flag`.
std::vector<nlohmann::json> parse_knob_values_text(const std::string& text, const std::string& flag);

/// A fronts results file as text tables, one per scene and front: each point's knobs, median
/// render time, error, bias and noise, whether the reference resolves its error, '*' on the
/// Pareto front.
void print_fronts(const nlohmann::json& results, std::FILE* out);

}  // namespace cli
