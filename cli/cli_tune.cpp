// `accelbench tune`: the best max_depth x max_leaf_size of a structure on one scene, and how
// flat the optimum is.

#include "cli/commands.h"
#include "cli/cli_shorthand.h"
#include "cli/cli_util.h"
#include "harness/sweep_definition.h"
#include "harness/sweep_results.h"
#include "harness/sweep_scene.h"
#include "harness/tune.h"
#include "cli/tune_accuracy_flags.h"

#include "accel/accel.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <tuple>

namespace cli {

using namespace harness;  // the command line drives the harness

namespace {

struct TuneFlags {
  std::string scene, accel = "kdtree", resolution = "320x240", json_out, max_memory = "0";
  /// The choice knobs' shorthand flags (--placement, --split): held fixed while the tree's
  /// size knobs are tuned.
  ShorthandValues held;
  int threads = 1, repetitions = 3, warmup = 1;
  std::string seed = "1";
  AccuracyTuneFlags accuracy;  ///< --max-error / --max-time: choose accuracy knobs instead.
};

/// "max_depth=9 max_leaf_size=6": the tuned knobs of a point.
std::string knobs_text(const TunePoint& p) {
  return (p.max_depth >= 0 ? "max_depth=" + std::to_string(p.max_depth) + " " : std::string()) +
         "max_leaf_size=" + std::to_string(p.max_leaf_size);
}

std::string range_text(int lo, int hi) {
  return lo == hi ? std::to_string(lo) : std::to_string(lo) + "-" + std::to_string(hi);
}

/// The shorthand flags tune holds fixed: the structures' choice knobs (the size knobs it tunes
/// are numbers).
std::vector<ShorthandFlag> held_flags() {
  std::vector<ShorthandFlag> out;
  for (ShorthandFlag& s : structure_shorthand_flags())
    if (s.choice) out.push_back(std::move(s));
  return out;
}

/// Every flag checked before anything is measured: a bad one is the only line of output.
TuneOptions options_from_flags(const TuneFlags& f, SceneSpec& spec) {
  try {
    spec = parse_scene_item(f.scene);
  } catch (const SweepError& e) {
    throw SweepError(std::string("SCENE: ") + e.what());
  }
  spec.seed = parse_seed(f.seed, "--seed");
  TuneOptions o;
  std::tie(o.measure.width, o.measure.height) = parse_resolution(f.resolution, "--resolution");
  o.measure.threads = f.threads;
  o.measure.repetitions = f.repetitions;
  o.measure.warmup = f.warmup;
  o.measure.limits.max_memory_bytes = parse_bytes(f.max_memory, "--max-memory");
  check_image_memory(o.measure.width, o.measure.height, o.measure.limits.max_memory_bytes, "--resolution");
  const auto knobs = structure_knobs(f.accel);
  if (!knobs) {
    std::string known;
    for (const std::string& n : accel::accel_names()) known += (known.empty() ? "" : ", ") + n;
    throw SweepError("--accel: '" + f.accel + "' cannot be built here (known: " + known + ")");
  }
  // A held knob is checked by the factory itself, over no primitives.
  for (const ShorthandFlag& s : held_flags()) {
    const std::vector<std::string>& given = f.held.at(s.knob);
    if (given.empty()) continue;
    if (std::find(knobs->begin(), knobs->end(), s.knob) == knobs->end())
      throw SweepError(s.flag + ": " + f.accel + " has no knob '" + s.knob + "'");
    try {
      accel::make_accel(f.accel, {{s.knob, given.back()}}, {});
    } catch (const std::exception& e) {
      throw SweepError(s.flag + ": " + e.what());
    }
    o.fixed[s.knob] = given.back();
  }
  return o;
}

int run(const TuneFlags& f) {
  SceneSpec spec;
  TuneOptions o = options_from_flags(f, spec);
  const tracer::Scene scene = load_sweep_scene(spec);
  // The structure at its default knobs must build on this scene within the budget, or every
  // point of the search would fail: say so once, naming the flag, before naive is measured.
  try {
    const auto boxes = scene.geometry.primitive_bounds();
    accel::make_accel(f.accel, o.fixed, boxes, o.measure.limits);
  } catch (const std::exception& e) {
    const std::string why = e.what();
    throw SweepError((why.find("--max-memory") != std::string::npos ? "--max-memory: " : "tune: ") + f.accel +
                     " cannot be built on " + spec.name + " at its default knobs: " + why);
  }

  std::printf("tune: %s on %s (%u primitives), %dx%d, %d thread(s); search: median of %d per point\n",
              f.accel.c_str(), spec.name.c_str(), scene.geometry.bounded_count(), o.measure.width, o.measure.height,
              f.threads, f.repetitions);
  const TuneResult r = tune(scene, f.accel, o);
  const TunePoint& best = r.points[r.best];
  std::size_t coarse = 0, valid = 0;
  for (const auto& p : r.points) coarse += p.round == 0, valid += p.m.status == RowStatus::Ok;
  std::printf("evaluated %zu points (%zu coarse, %zu refined, %zu valid)\n", r.points.size(), coarse,
              r.points.size() - coarse, valid);
  std::printf("confirmed: the best %zu of the search and naive, %d interleaved rounds; median [95%% interval], "
              "and the ratio to the fastest paired by round:\n",
              r.candidates.size(), r.confirm_rounds);
  for (std::size_t i : r.candidates) {
    const auto& p = r.points[i];
    const Confirmation& c = *p.confirmed;
    std::printf("  %-30s %9.3f ms [%.3f, %.3f]  x%.3f [%.3f, %.3f]%s\n", knobs_text(p).c_str(), c.render_ms.median,
                c.render_ms_ci.lo, c.render_ms_ci.hi, c.ratio, c.ratio_ci.lo, c.ratio_ci.hi,
                i == r.best ? "  fastest" : "");
  }
  const Confirmation& bc = *best.confirmed;
  if (r.separated) {
    std::printf("winner: %s: %.3f ms [%.3f, %.3f], %.1fx naive [%.1f, %.1f] (every other candidate is slower at 95%%)\n",
                knobs_text(best).c_str(), bc.render_ms.median, bc.render_ms_ci.lo, bc.render_ms_ci.hi, r.best_speedup,
                r.best_speedup_ci.lo, r.best_speedup_ci.hi);
  } else {
    std::string names;
    for (std::size_t i : r.tie) names += (names.empty() ? "" : ", ") + knobs_text(r.points[i]);
    std::printf("tie: %zu candidates cannot be told apart at 95%%: %s\n", r.tie.size(), names.c_str());
    std::printf("      the fastest median: %s: %.3f ms [%.3f, %.3f], %.1fx naive [%.1f, %.1f]\n",
                knobs_text(best).c_str(), bc.render_ms.median, bc.render_ms_ci.lo, bc.render_ms_ci.hi,
                r.best_speedup, r.best_speedup_ci.lo, r.best_speedup_ci.hi);
  }
  std::printf("      every knob: %s\n", best.m.params.dump().c_str());
  int dlo = 1 << 30, dhi = -1, llo = 1 << 30, lhi = -1;
  for (std::size_t i : r.flat) {
    const auto& p = r.points[i];
    dlo = std::min(dlo, p.max_depth), dhi = std::max(dhi, p.max_depth);
    llo = std::min(llo, p.max_leaf_size), lhi = std::max(lhi, p.max_leaf_size);
  }
  std::printf("flat region (not shown slower than the fastest by more than %.0f%%): %zu of %zu confirmed points",
              100.0 * o.flat_tolerance, r.flat.size(), r.candidates.size());
  if (best.max_depth >= 0) std::printf(", max_depth %s", range_text(dlo, dhi).c_str());
  std::printf(", max_leaf_size %s\n", range_text(llo, lhi).c_str());
  if (!f.json_out.empty()) {
    nlohmann::json j = to_json(r);
    j["scene"] = to_json(spec);
    write_json_atomic(f.json_out, j);
    std::printf("wrote %s\n", f.json_out.c_str());
  }
  return 0;
}

}  // namespace

void add_tune_command(CLI::App& app, int& exit_code) {
  auto flags = std::make_shared<TuneFlags>();
  CLI::App* cmd = app.add_subcommand(
      "tune",
      "Find a structure's best max_depth x max_leaf_size on a scene (coarse grid, refinement, then the best "
      "candidates timed again, interleaved, to confirm the winner or report a tie); with --max-error or "
      "--max-time, the accuracy knobs that meet the budget (docs/accuracy.md)");
  cmd->add_option("scene", flags->scene, "Generator name, generator:count, or scene file (.json, .nff)")
      ->required();
  cmd->add_option("--accel", flags->accel, "Structure to tune")->capture_default_str();
  cmd->add_option("--threads", flags->threads, "Render threads (0 = all cores)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  cmd->add_option("--resolution", flags->resolution, "Image size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--repetitions", flags->repetitions, "Timed renders per point (median used)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--warmup", flags->warmup, "Untimed renders before them")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  add_shorthand_flags(*cmd, held_flags(), flags->held, /*list=*/false);
  cmd->add_option("--max-memory", flags->max_memory, "Build memory budget, e.g. 512M or 2G (0 = 25% of RAM)");
  cmd->add_option("--seed", flags->seed, "Generator seed, an integer in [0, 2^64-1]")->capture_default_str();
  cmd->add_option("--json", flags->json_out, "Also write every point as JSON to this file");
  add_accuracy_tune_flags(*cmd, flags->accuracy);
  cmd->callback([flags, &exit_code] {
    const TuneFlags& f = *flags;
    exit_code = accuracy_tune_requested(f.accuracy)
                    ? run_accuracy_tune(f.accuracy,
                                        TuneCommon{f.scene, f.accel, f.resolution, f.seed,
                                                   f.threads, f.repetitions, f.warmup},
                                        f.json_out)
                    : run(f);
  });
}

}  // namespace cli
