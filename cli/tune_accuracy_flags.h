#pragma once
// The accuracy flags of `accelbench tune` (--max-error, --max-time, --fronts, --front and the
// fronts flags tune lacks) and the run they start: fronts measured first when no results file
// is given, then harness/tune_accuracy.h chooses.

#include "cli/fronts_flags.h"
#include "harness/tune_accuracy.h"

#include <string>

namespace CLI {
class App;
}  // namespace CLI

namespace cli {

using namespace harness;  // the command line drives the harness

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

}  // namespace cli
