#include "cli/tune_accuracy_flags.h"

#include "harness/fronts.h"
#include "harness/sweep_definition.h"
#include "harness/sweep_results.h"
#include "harness/sweep_runner.h"
#include "harness/sweep_scene.h"

#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>

namespace cli {

using namespace harness;  // the command line drives the harness

namespace {

using nlohmann::json;

double parse_positive(const std::string& text, const std::string& flag) {
  double v = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(v) || v < 0.0)
    throw SweepError(flag + ": expected a number >= 0, got '" + text + "'");
  return v;
}

}  // namespace

void add_accuracy_tune_flags(CLI::App& cmd, AccuracyTuneFlags& f) {
  cmd.add_option("--max-error", f.max_error,
                 "Accuracy tuning: the fastest configuration whose error (--metric) is at most this");
  cmd.add_option("--max-time", f.max_time,
                 "Accuracy tuning: the most accurate configuration rendering within this many ms");
  cmd.add_option("--fronts", f.fronts_file, "Choose from this results file of accelbench fronts");
  cmd.add_option("--front", f.front, "Only the front of this knob group (e.g. max_depth)");
  cmd.add_option("--knobs", f.fronts.knobs, "Without --fronts: the knobs to measure fronts of (see fronts --help)");
  cmd.add_option("--values", f.fronts.values, "Without --fronts: KNOB=v1,v2,... or KNOB=LO:HI:N");
  cmd.add_option("--set", f.fronts.set, "Without --fronts: KNOB=VALUE held in every render");
  cmd.add_option("--metric", f.fronts.metric, "Without --fronts: rmse or rel_mse")->capture_default_str();
  cmd.add_option("--seeds", f.fronts.seeds, "Without --fronts: renders per configuration for bias/variance")
      ->check(CLI::Range(1, 1024));
  cmd.add_option("--cache", f.fronts.cache, "Without --fronts: reference cache directory");
  cmd.add_flag("--no-cache", f.fronts.no_cache, "Without --fronts: neither read nor write cached references");
}

bool accuracy_tune_requested(const AccuracyTuneFlags& f) { return !f.max_error.empty() || !f.max_time.empty(); }

int run_accuracy_tune(const AccuracyTuneFlags& f, const TuneCommon& common, const std::string& json_out) {
  if (!f.max_error.empty() && !f.max_time.empty())
    throw SweepError("--max-error and --max-time: give one of them");
  const bool by_error = !f.max_error.empty();
  const double budget = by_error ? parse_positive(f.max_error, "--max-error") : parse_positive(f.max_time, "--max-time");
  SceneSpec spec;
  try {
    spec = parse_scene_item(common.scene);
  } catch (const SweepError& e) {
    throw SweepError(std::string("SCENE: ") + e.what());
  }
  json results;
  std::string source;
  if (!f.fronts_file.empty()) {
    if (!f.fronts.knobs.empty()) throw SweepError("--knobs: give either --fronts FILE or --knobs, not both");
    results = read_results_file(f.fronts_file);
    source = f.fronts_file;
  } else {
    if (f.fronts.knobs.empty()) throw SweepError("--max-error/--max-time: give --fronts FILE or --knobs LIST");
    FrontsFlags ff = f.fronts;
    ff.scenes = {common.scene};
    ff.accel = common.accel;
    ff.resolution = common.resolution;
    ff.seed = common.seed;
    ff.threads = common.threads;
    ff.repetitions = common.repetitions;
    ff.warmup = common.warmup;
    const SweepDefinition d = fronts_definition(request_from_flags(ff));
    RunOptions o;
    o.out_path = "results/" + d.name + ".json";
    o.jsonl_path = "results/" + d.name + ".jsonl";
    o.resume = true;  // the same request continues (or reuses) its own earlier run
    ReferenceOptions ro = reference_options_from_flags(ff);
    run_fronts(d, o, ro);
    results = read_results_file(o.out_path);
    source = o.out_path;
  }
  const AccuracyChoice c = by_error ? choose_within_error(results, spec.name, budget, f.front)
                                    : choose_within_time(results, spec.name, budget, f.front);
  std::printf("tune: %s on %s (front %s, from %s): %s\n", by_error ? "fastest within the error budget" : "most accurate within the time budget",
              c.scene.c_str(), c.front.c_str(), source.c_str(), c.row.value("integrator_params", json::object()).dump().c_str());
  std::printf("  measured: %.3f ms median, %s %.4g (budget: %s %s)\n", c.render_ms, c.metric.c_str(), c.error,
              by_error ? c.metric.c_str() : "time", by_error ? four_significant(budget).c_str() : (four_significant(budget) + " ms").c_str());
  std::printf("  the front it came from (fastest first):\n");
  for (const json& p : c.pareto)
    std::printf("    %-10s %-32s %10.3f ms  %s %.4g%s\n", p["front"].get<std::string>().c_str(),
                p["integrator_params"].dump().c_str(), p["render_ms"].get<double>(), c.metric.c_str(),
                p["error"].get<double>(), p["key"] == c.row["key"] ? "   <- chosen" : "");
  if (!json_out.empty()) {
    std::ofstream out(json_out);
    out << to_json(c).dump(2) << '\n';
    if (!out) throw SweepError("--json: cannot write '" + json_out + "'");
  }
  return 0;
}

}  // namespace cli
