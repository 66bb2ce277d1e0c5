#pragma once
// The final results file: machine, sweep definition, shard, runs and rows, assembled from the
// JSON Lines records of a sweep; and the merge of several shards' results into one.

#include "harness/sweep_definition.h"

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace harness {

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

/// The configurations of a sweep by key.
std::map<std::string, const SweepConfig*> configs_by_key(const std::vector<SweepConfig>& configs);

/// Checks that `row` is a row of one of `configs`: "key" a string naming a configuration, "index"
/// that configuration's index, "scene", "structure", "requested" and "integrator_params" (absent
/// for none) matching it, "status" one of
/// ok, failed, error, and an ok row's render_ms median a number >= 0. Returns the configuration.
/// Throws SweepError "<where>/<field>: <what is wrong>".
const SweepConfig& check_row(const nlohmann::json& row, const std::map<std::string, const SweepConfig*>& configs,
                             const SweepDefinition& definition, const std::string& where);

/// Parses the text of a results file strictly (input::parse_json) and checks it: format and
/// version, "machine", "sweep" (a valid definition), "shard" (0 <= index < count), and every row
/// (check_row, in its shard, no configuration twice). Throws SweepError "<name>: <pointer>: ...".
nlohmann::json parse_results_text(std::string_view text, const std::string& name);

/// Reads (a regular file within input::kMaxResultsFileBytes) and checks a results file. Throws
/// SweepError naming the path.
nlohmann::json read_results_file(const std::string& path);

/// Joins shards (path, document): same sweep definition, no configuration twice (SweepError
/// otherwise). The merged document's "missing" lists configurations no input holds; "machines"
/// lists the inputs' distinct machines when there are several, and "mixed_hardware" says when
/// they differ in CPU model or core count.
nlohmann::json merge_results(const std::vector<std::pair<std::string, nlohmann::json>>& inputs);

}  // namespace harness
