#pragma once
// Runs a sweep: measures every pending configuration scene by scene, appends each row to the
// JSON Lines file as soon as it is measured, and writes the results file at the end (also after
// SIGINT/SIGTERM, with what is done).

#include "harness/sweep_definition.h"
#include "harness/sweep_measure.h"

#include <functional>
#include <string>

namespace harness {

/// Where and how to run a sweep.
struct RunOptions {
  std::string out_path;      ///< Final results JSON.
  std::string jsonl_path;    ///< Row-by-row JSON Lines file.
  bool resume = false;       ///< Keep the JSON Lines file's rows and skip their configurations.
  int shard_index = 0;       ///< This shard, 0-based.
  int shard_count = 1;       ///< Number of shards.
  bool progress = true;      ///< Progress lines on stderr.
  Inspector inspect;         ///< Optional: sees every ok configuration's image (fronts).
  /// Folder for the rows' images when the sweep saves them ("images": true); "" = beside the
  /// JSON Lines file, named after it with "-images".
  std::string images_dir;
  /// Called after each row is written, with the rows this run has written so far; empty: none.
  /// The tests stop the process there (a real SIGKILL or SIGTERM at a known row).
  std::function<void(std::size_t rows_written)> after_row;
};

/// What a run did.
struct RunSummary {
  std::size_t shard_configs = 0;   ///< Configurations in this shard.
  std::size_t already_done = 0;    ///< Skipped because the JSON Lines file had them (--resume).
  std::size_t measured = 0;        ///< Rows written by this run.
  std::size_t not_ok = 0;          ///< Of those, rows with status failed or error.
  std::size_t rows = 0;            ///< Rows in the results file (earlier runs' included).
  std::size_t ok_rows = 0;         ///< Of those, rows with status ok.
  double wall_s = 0.0;             ///< Wall time of the run, s.
  double build_s = 0.0;            ///< Time inside structure builds, s.
  double trace_s = 0.0;            ///< Time inside render calls (timed, warm-up, counting), s.
  bool interrupted = false;        ///< Stopped early by SIGINT/SIGTERM.
  bool complete = false;           ///< The results file holds every configuration of the shard.
  std::string hardware_warning;  ///< Set when the shard's rows were measured on different hardware.

  /// Harness overhead: wall time outside builds and renders, as a fraction of wall time.
  double harness_fraction() const { return wall_s > 0 ? (wall_s - build_s - trace_s) / wall_s : 0.0; }
};

/// Sets where a run called `name` writes, from its shard: the results file `out`, else
/// results/NAME.json (a shard of several: results/NAME.shardIofN.json), and the JSON Lines file
/// `jsonl`, else the results file with the extension .jsonl.
void set_output_paths(RunOptions& options, const std::string& name, const std::string& out, const std::string& jsonl);

/// Runs the sweep. Throws SweepError for unusable files (e.g. --resume on another sweep's file).
/// SIGINT and SIGTERM stop it cleanly after the batch being written (see RunOptions::after_row
/// for how the tests stop it at a chosen row).
RunSummary run_sweep(const SweepDefinition& definition, const RunOptions& options);

}  // namespace harness
