// `accelbench merge`: joins the results files of a sharded sweep into one.

#include "cli/commands.h"
#include "harness/fronts.h"
#include "harness/sweep_results.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace cli {

using namespace harness;  // the command line drives the harness

namespace {

struct MergeFlags {
  std::vector<std::string> inputs;
  std::string out;
};

int run(const MergeFlags& f) {
  std::vector<std::pair<std::string, nlohmann::json>> docs;
  for (const auto& path : f.inputs) docs.emplace_back(path, read_results_file(path));
  nlohmann::json merged = merge_results(docs);
  annotate_fronts(merged);  // fronts shards: the Pareto fronts over every shard's rows
  write_json_atomic(f.out, merged);
  const auto& missing = merged["missing"];
  std::fprintf(stderr, "merge: wrote %s: %zu rows from %zu files\n", f.out.c_str(), merged["rows"].size(),
               docs.size());
  if (merged.contains("mixed_hardware"))
    std::fprintf(stderr, "merge: warning: %s\n",
                 merged["mixed_hardware"]["warning"].get<std::string>().c_str());
  if (!missing.empty()) {
    std::fprintf(stderr, "merge: %zu configuration(s) missing, e.g. %s\n", missing.size(),
                 missing[0].get<std::string>().c_str());
    return 2;
  }
  return 0;
}

}  // namespace

void add_merge_command(CLI::App& app, int& exit_code) {
  auto flags = std::make_shared<MergeFlags>();
  CLI::App* cmd = app.add_subcommand("merge", "Join the results files of sweep shards (--shard i/n) into one");
  cmd->add_option("inputs", flags->inputs, "Results JSON files of the shards")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--out", flags->out, "Merged results JSON")->required();
  cmd->callback([flags, &exit_code] { exit_code = run(*flags); });
}

}  // namespace cli
