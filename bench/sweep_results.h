#pragma once
// The final results file: machine, sweep definition, shard, runs and rows, assembled from the
// JSON Lines records of a sweep; and the merge of several shards' results into one.

#include "sweep_definition.h"

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace bench {

/// Format name and version written into every results file.
inline constexpr const char* kResultsFormat = "accelbench-results";
inline constexpr int kResultsVersion = 1;

/// Record kinds in the JSON Lines file.
inline constexpr const char* kHeaderKind = "header";
inline constexpr const char* kRowKind = "row";
inline constexpr const char* kRunKind = "run";
/// Written when a run resumes a file: the machine it resumed on.
inline constexpr const char* kResumeKind = "resume";

/// The results document of one shard from its JSON Lines records (a header, rows, run and resume
/// records). `expected` lists the shard's configurations; rows are ordered by index, repeats
/// dropped. `machine` is the header's; resumes on other nodes add "machines" and, on other
/// hardware, "mixed_hardware".
nlohmann::json assemble_results(const std::vector<nlohmann::json>& records, const nlohmann::json& machine,
                                const SweepDefinition& definition, int shard_index, int shard_count,
                                const std::vector<SweepConfig>& expected);

/// Writes `doc` to `path` through a temporary file and a rename, so a reader never sees half a
/// file. Throws SweepError.
void write_json_atomic(const std::string& path, const nlohmann::json& doc);

/// Reads a results file and checks its format. Throws SweepError naming the path.
nlohmann::json read_results_file(const std::string& path);

/// Joins shards (path, document): same sweep definition, no configuration twice (SweepError
/// otherwise). The merged document's "missing" lists configurations no input holds; "machines"
/// lists the inputs' distinct machines when there are several, and "mixed_hardware" says when
/// they differ in CPU model or core count.
nlohmann::json merge_results(const std::vector<std::pair<std::string, nlohmann::json>>& inputs);

}  // namespace bench
