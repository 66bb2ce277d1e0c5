#pragma once
// --resume: what an earlier run's JSON Lines file holds, checked record by record against the
// sweep definition and shard before a single configuration is skipped.

#include "harness/sweep_definition.h"
#include "harness/sweep_jsonl.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace harness {

/// The usable part of an earlier run's JSON Lines file.
struct ResumeState {
  std::vector<nlohmann::json> records;          ///< Header, rows and run records, in file order.
  std::map<std::string, nlohmann::json> done;   ///< Rows by configuration key.
  nlohmann::json machine;                       ///< The header's machine description.
  std::uint64_t valid_bytes = 0;                ///< Bytes up to the last complete line.
  bool torn_tail = false;                       ///< A line cut by a kill follows them (to be cut off).
};

/// Checks `contents` (read from `name`) for resuming the shard `shard_json` (its configurations
/// `mine`) of `definition`: line 1 must be a header of this sweep definition and shard; every
/// row must be a configuration of this shard (bench::check_row: key, index, scene, structure,
/// requested, status) and appear once; every other record must be a resume record (with its
/// machine) or a run record. Throws
/// SweepError "<name>:<line>: <what is wrong>; cannot --resume" at the first record it cannot
/// place: a resume never drops a configuration and never keeps one it cannot account for. An
/// empty file gives an empty state (a fresh start).
ResumeState check_resume(const JsonlContents& contents, const std::string& name, const SweepDefinition& definition,
                         const nlohmann::json& shard_json, const std::vector<SweepConfig>& mine);

}  // namespace harness
