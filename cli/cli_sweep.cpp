// `accelbench sweep`: structures x knobs x scenes from a sweep file and flags, measured into a
// JSON Lines file row by row and a results JSON at the end.

#include "cli/commands.h"
#include "cli/cli_shorthand.h"
#include "cli/cli_util.h"
#include "harness/cpu_pinning.h"
#include "harness/sweep_definition.h"
#include "harness/sweep_runner.h"
#include "integrators/integrators.h"

#include "accel/accel.h"
#include "knobs/knob_table.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <set>
#include <string>
#include <vector>

#ifndef ACCELBENCH_SOURCE_DIR
#define ACCELBENCH_SOURCE_DIR "."
#endif

namespace cli {

using namespace harness;  // the command line drives the harness

namespace {

struct SweepFlags {
  std::string config;
  std::vector<std::string> scenes, accel;
  ShorthandValues structure_flags;  ///< --max-depth 4,8,12 ...: the tables' shorthands.
  std::vector<std::string> knobs;  ///< --knob NAME=V1[,V2...], any structure knob.
  int repetitions = -1, warmup = -1, threads = -1;
  std::string resolution, out, jsonl, shard_text = "0/1", max_memory;
  std::string validate_resolution, integrator;
  std::vector<std::string> integrator_knobs;  ///< --param NAME=V1,V2,...
  bool resume = false, quiet = false, spd = false, list = false, no_pin = false;
};

/// A knob flag replaces that knob's values everywhere in the definition.
void override_knob(SweepDefinition& d, const std::string& knob, const std::vector<nlohmann::json>& values) {
  if (values.empty()) return;
  for (auto& s : d.structures)
    if (s.knobs.count(knob)) s.knobs[knob] = values;
  d.knobs[knob] = values;
}

/// A knob flag's values replace that knob's values everywhere; a knob no swept structure has is
/// an error naming the flag.
void override_knob_flag(SweepDefinition& d, const std::string& flag, const std::string& knob,
                        const std::vector<nlohmann::json>& values) {
  if (values.empty()) return;
  bool someone_has_it = false, all_probed = true;
  std::string swept;
  for (const auto& s : d.structures) {
    swept += (swept.empty() ? "" : ", ") + s.name;
    const auto knobs = structure_knobs(s.name);
    if (!knobs) all_probed = false;
    else if (std::find(knobs->begin(), knobs->end(), knob) != knobs->end()) someone_has_it = true;
  }
  if (!someone_has_it && all_probed)
    throw SweepError(flag + ": no swept structure has the knob " + knob + " (swept: " + swept + ")");
  override_knob(d, knob, values);
}

SweepDefinition definition_from_flags(const SweepFlags& f) {
  const std::string path = f.config.empty() ? std::string(ACCELBENCH_SOURCE_DIR) + "/sweeps/paper.json" : f.config;
  SweepDefinition d = load_sweep_file(path);  // the file alone is valid, or its errors name it
  if (!f.scenes.empty()) {
    d.scenes.clear();
    std::set<std::string> names;
    for (const auto& item : f.scenes) {
      try {
        d.scenes.push_back(parse_scene_item(item));
      } catch (const SweepError& e) {
        throw SweepError(std::string("--scenes: ") + e.what());
      }
      if (!names.insert(d.scenes.back().name).second)
        throw SweepError("--scenes: scene name '" + d.scenes.back().name + "' is given twice");
    }
  }
  if (!f.accel.empty()) {
    const auto names = accel::accel_names();
    // Keep the file's entries for the listed structures (with their knobs); add the others.
    std::vector<StructureSpec> kept;
    for (const auto& name : f.accel) {
      if (std::find(names.begin(), names.end(), name) == names.end() && name != "embree") {
        std::string known;
        for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
        throw SweepError("--accel: unknown structure '" + name + "' (known: " + known + ")");
      }
      bool found = false;
      for (const auto& s : d.structures)
        if (s.name == name) {
          kept.push_back(s);
          found = true;
        }
      if (!found) kept.push_back(StructureSpec{name, {}});
    }
    d.structures = kept;
  }
  for (const ShorthandFlag& s : structure_shorthand_flags()) {
    std::vector<nlohmann::json> values;
    for (const std::string& text : f.structure_flags.at(s.knob)) values.push_back(knobs::knob_value_from_text(text));
    override_knob_flag(d, s.flag, s.knob, values);
  }
  for (const std::string& text : f.knobs) {
    const std::string name = knobs::parse_knob_assignment(text).first;
    std::vector<nlohmann::json> values;
    const std::string list = text.substr(text.find('=') + 1);
    for (std::size_t at = 0;;) {
      const std::size_t comma = list.find(',', at);
      values.push_back(knobs::knob_value_from_text(list.substr(at, comma - at)));
      if (comma == std::string::npos) break;
      at = comma + 1;
    }
    override_knob_flag(d, "--knob", name, values);
  }
  if (f.repetitions >= 0) d.repetitions = f.repetitions;
  if (f.warmup >= 0) d.warmup = f.warmup;
  if (f.threads >= 0) d.threads = f.threads;
  if (!f.max_memory.empty()) d.max_memory_bytes = parse_bytes(f.max_memory, "--max-memory");
  if (!f.resolution.empty()) std::tie(d.width, d.height) = parse_resolution(f.resolution, "--resolution");
  if (f.spd && !f.integrator.empty() && f.integrator != "spd")
    throw SweepError("--spd: is --integrator spd, but --integrator " + f.integrator + " was given");
  if (f.spd) d.integrator = "spd";
  if (!f.integrator.empty()) d.integrator = integrators::named(f.integrator, "--integrator").name;
  for (const std::string& item : f.integrator_knobs) {
    // NAME=V1,V2,...: each value read as JSON when it parses, else as a string.
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) throw SweepError("--param: expected NAME=V1,V2,..., got '" + item + "'");
    std::vector<nlohmann::json> values;
    std::string rest = item.substr(eq + 1);
    for (std::size_t start = 0;;) {
      const std::size_t comma = rest.find(',', start);
      const std::string text = rest.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      nlohmann::json v = nlohmann::json::parse(text, nullptr, false);
      values.push_back(v.is_discarded() ? nlohmann::json(text) : v);
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    // Like a structure knob flag, it replaces the knob's values in every group (one group when
    // the file has none).
    if (d.integrator_knobs.empty()) d.integrator_knobs.emplace_back();
    for (KnobValues& group : d.integrator_knobs) group[item.substr(0, eq)] = values;
  }
  if (!f.validate_resolution.empty())
    std::tie(d.validate_width, d.validate_height) =
        parse_resolution(f.validate_resolution, "--validate-resolution");
  // Re-validate the edited definition so flags get the same checks as the file; knobs no swept
  // structure has are dropped from the sweep-wide set (the file's own, for structures that
  // --accel removed).
  std::vector<std::string> known;
  for (const auto& s : d.structures)
    if (const auto k = structure_knobs(s.name)) known.insert(known.end(), k->begin(), k->end());
  for (auto it = d.knobs.begin(); it != d.knobs.end();)
    it = std::find(known.begin(), known.end(), it->first) == known.end() ? d.knobs.erase(it) : std::next(it);
  try {
    return parse_sweep_definition(to_json(d));
  } catch (const SweepError& e) {
    // The file alone was valid: what fails now is the file combined with the flags.
    throw SweepError(path + " with the flags given: " + e.what());
  }
}

int run(const SweepFlags& f, const Hooks& hooks) {
  const SweepDefinition d = definition_from_flags(f);
  RunOptions o;
  o.after_row = hooks.after_sweep_row;
  std::tie(o.shard_index, o.shard_count) = parse_shard(f.shard_text);
  if (f.list) {
    for (const auto& c : shard(expand(d), o.shard_index, o.shard_count))
      std::printf("%s\n", c.key.c_str());
    return 0;
  }
  set_output_paths(o, d.name, f.out, f.jsonl);
  o.resume = f.resume;
  o.progress = !f.quiet;
  // One render thread stays on the CPU it starts on: moved between the two vCPUs of a VM, the
  // same render took up to 18% longer, unequally per structure (docs/sweeps.md).
  const int pinned = d.threads == 1 && !f.no_pin ? pin_to_current_cpu() : -1;
  if (!f.quiet && pinned >= 0)
    std::fprintf(stderr, "sweep: one render thread, kept on CPU %d (--no-pin leaves it free)\n", pinned);
  if (!f.quiet)
    std::fprintf(stderr, "sweep: %s: %zu scene(s), %zu structure entr%s, shard %d/%d -> %s (rows: %s)\n",
                 d.name.c_str(), d.scenes.size(), d.structures.size(), d.structures.size() == 1 ? "y" : "ies",
                 o.shard_index, o.shard_count, o.out_path.c_str(), o.jsonl_path.c_str());
  const RunSummary s = run_sweep(d, o);
  std::fprintf(stderr,
               "sweep: %s %s: %zu of %zu configurations (%zu measured now, %zu failed or in error); "
               "wall %.1f s, build %.1f s, trace %.1f s, harness overhead %.2f%%\n",
               s.interrupted ? "interrupted, wrote" : "wrote", o.out_path.c_str(), s.already_done + s.measured,
               s.shard_configs, s.measured, s.not_ok, s.wall_s, s.build_s, s.trace_s, 100.0 * s.harness_fraction());
  if (!s.hardware_warning.empty())
    std::fprintf(stderr, "sweep: warning: %s\n", s.hardware_warning.c_str());
  if (s.interrupted) {
    std::fprintf(stderr, "sweep: continue with the same flags and --resume\n");
    return 130;
  }
  if (s.rows > 0 && s.ok_rows == 0)
    throw SweepError("sweep: every configuration failed or is in error (" + std::to_string(s.rows) +
                     (s.rows == 1 ? " row" : " rows") + "; the reasons are in " + o.out_path + ")");
  return 0;
}

}  // namespace

void add_sweep_command(CLI::App& app, int& exit_code, const Hooks& hooks) {
  auto flags = std::make_shared<SweepFlags>();
  CLI::App* cmd = app.add_subcommand(
      "sweep", "Measure structures x max_depth x max_leaf_size (x placement x split) x scenes");
  cmd->add_option("--config", flags->config, "Sweep definition JSON (default: sweeps/paper.json)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--scenes", flags->scenes, "Scenes: generator, generator:count, or scene file (.json, .nff)")
      ->delimiter(',');
  cmd->add_option("--accel", flags->accel, "Structures to sweep, e.g. naive,octree,kdtree")->delimiter(',');
  add_shorthand_flags(*cmd, structure_shorthand_flags(), flags->structure_flags, /*list=*/true);
  cmd->add_option("--knob", flags->knobs,
                  "Values of any structure knob, NAME=V1[,V2...], repeatable (see `accelbench structures`)");
  cmd->add_option("--repetitions", flags->repetitions, "Timed renders per configuration (median reported)")
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--warmup", flags->warmup, "Untimed renders before the timed ones")->check(CLI::Range(0, 10000));
  cmd->add_option("--threads", flags->threads, "Render threads (0 = all cores)")->check(CLI::Range(0, 4096));
  cmd->add_option("--resolution", flags->resolution, "Image size WIDTHxHEIGHT (default: the sweep file's)");
  cmd->add_option("--integrator", flags->integrator,
                  "Integrator of every configuration (sweep key \"integrator\"); one of " + integrators::names());
  cmd->add_flag("--spd", flags->spd, "Shorthand for --integrator spd (the SPD test rules)");
  cmd->add_option("--param", flags->integrator_knobs,
                  "Integrator knob values to cross, NAME=V1,V2,... (sweep key \"integrator_knobs\"; "
                  "replaces the knob's values in every group), e.g. --param cone_k=1,1.5,2")
      ->allow_extra_args(false);
  cmd->add_option("--validate-resolution", flags->validate_resolution,
                  "Render naive and check every structure against it at WIDTHxHEIGHT only; no speedups then");
  cmd->add_option("--max-memory", flags->max_memory, "Build memory budget, e.g. 512M or 2G (0 = 25% of RAM)");
  cmd->add_option("--out", flags->out, "Results JSON (default results/<sweep name>.json)");
  cmd->add_option("--jsonl", flags->jsonl, "Row-by-row JSON Lines file (default: --out with .jsonl)");
  cmd->add_flag("--resume", flags->resume, "Keep the JSON Lines file's rows and skip those configurations");
  cmd->add_option("--shard", flags->shard_text, "Run shard I of N (0-based), e.g. 0/4");
  cmd->add_flag("--quiet", flags->quiet, "No progress lines");
  cmd->add_flag("--no-pin", flags->no_pin,
                "With one render thread, let it move between CPUs (by default it stays on the CPU it starts on)");
  cmd->add_flag("--list", flags->list,
                "Check the definition, print the shard's configuration keys one a line, and exit");
  cmd->callback([flags, hooks, &exit_code] { exit_code = run(*flags, hooks); });
}

}  // namespace cli
