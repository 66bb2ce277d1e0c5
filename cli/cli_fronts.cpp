// `accelbench fronts SCENE... --knobs LIST`: error against an independent reference and render
// time for each value of each accuracy knob, the Pareto front marked (docs/accuracy.md).

#include "cli/commands.h"
#include "harness/accuracy_knobs.h"
#include "harness/fronts.h"
#include "cli/fronts_flags.h"
#include "harness/sweep_results.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>
#include <string>

namespace cli {

using namespace harness;  // the command line drives the harness

namespace {

struct FrontsCliFlags {
  FrontsFlags fronts;
  std::string out, jsonl, shard_text = "0/1";
  bool resume = false, quiet = false;
};

int run(const FrontsCliFlags& f) {
  const FrontsRequest request = request_from_flags(f.fronts);
  const SweepDefinition d = fronts_definition(request);
  RunOptions o;
  std::tie(o.shard_index, o.shard_count) = parse_shard(f.shard_text);
  set_output_paths(o, d.name, f.out, f.jsonl);
  o.resume = f.resume;
  o.progress = !f.quiet;
  ReferenceOptions ro = reference_options_from_flags(f.fronts);
  ro.progress = !f.quiet;
  if (!f.quiet)
    std::fprintf(stderr, "fronts: %s: %zu scene(s), %zu knob group(s), %s through %s, shard %d/%d -> %s (references: %s)\n",
                 d.name.c_str(), d.scenes.size(), d.integrator_knobs.size(), d.integrator.c_str(),
                 request.structure.c_str(), o.shard_index, o.shard_count, o.out_path.c_str(),
                 ro.cache_dir.empty() ? "not cached" : ro.cache_dir.c_str());
  const FrontsSummary s = run_fronts(d, o, ro);
  print_fronts(read_results_file(o.out_path), stdout);
  std::fprintf(stderr,
               "fronts: %s %s: %zu of %zu configurations (%zu measured now, %zu failed or in error); references: "
               "%d rendered, %d from the cache (%.1f s); wall %.1f s, build %.1f s, renders %.1f s; fronts add "
               "%.2f%% over the renders\n",
               s.sweep.interrupted ? "interrupted, wrote" : "wrote", o.out_path.c_str(),
               s.sweep.already_done + s.sweep.measured, s.sweep.shard_configs, s.sweep.measured, s.sweep.not_ok,
               s.references_made, s.references_cached, s.reference_s, s.wall_s, s.sweep.build_s, s.sweep.trace_s,
               100.0 * s.overhead_fraction);
  if (s.sweep.interrupted) {
    std::fprintf(stderr, "fronts: continue with the same flags and --resume\n");
    return 130;
  }
  return 0;
}

}  // namespace

void add_fronts_command(CLI::App& app, int& exit_code) {
  auto flags = std::make_shared<FrontsCliFlags>();
  CLI::App* cmd = app.add_subcommand(
      "fronts", "Speed/accuracy fronts: render time and error against a reference for each accuracy knob");
  add_fronts_flags(*cmd, flags->fronts);
  cmd->add_option("--out", flags->out, "Results JSON (default results/<name>.json)");
  cmd->add_option("--jsonl", flags->jsonl, "Row-by-row JSON Lines file (default: --out with .jsonl)");
  cmd->add_flag("--resume", flags->resume, "Keep the JSON Lines file's rows and skip those configurations");
  cmd->add_option("--shard", flags->shard_text, "Run shard I of N (0-based), e.g. 0/4");
  cmd->add_flag("--quiet", flags->quiet, "No progress lines");
  cmd->callback([flags, &exit_code] { exit_code = run(*flags); });
}

}  // namespace cli
