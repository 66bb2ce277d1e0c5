#include "tune_accuracy.h"

#include "pareto.h"
#include "sweep_definition.h"
#include "sweep_results.h"

#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <vector>

namespace bench {

namespace {

using nlohmann::json;

/// The ok rows of `scene` (and `front`) with a finite error, as points.
struct Pool {
  std::string metric;
  std::vector<const json*> rows;
  std::vector<TimeError> points;
};

Pool pool_of(const json& results, const std::string& scene, const std::string& front, const std::string& flag) {
  if (!results.contains("sweep") || !results["sweep"].contains("fronts"))
    throw SweepError(flag + ": the results file is not from accelbench fronts");
  const FrontsSettings settings = fronts_settings_from_json(results["sweep"]["fronts"]);
  Pool p;
  p.metric = metric_name(settings.metric);
  bool scene_seen = false, front_seen = front.empty();
  for (const json& row : results["rows"]) {
    if (row.value("scene", "") != scene) continue;
    scene_seen = true;
    if (!front.empty() && row.value("front", "") != front) continue;
    front_seen = true;
    if (row.value("status", "") != "ok" || !row.contains("error")) continue;
    const json& e = row["error"][p.metric];
    if (!e.is_number()) continue;
    p.rows.push_back(&row);
    p.points.push_back({row["render_ms"]["median"].get<double>(), e.get<double>()});
  }
  if (!scene_seen) throw SweepError(flag + ": the results have no rows of scene '" + scene + "'");
  if (!front_seen) throw SweepError("--front: the results have no front '" + front + "' on scene '" + scene + "'");
  if (p.rows.empty()) throw SweepError(flag + ": no configuration of scene '" + scene + "' was measured ok");
  return p;
}

AccuracyChoice choice(const Pool& p, const std::string& scene, std::size_t i) {
  AccuracyChoice c;
  c.scene = scene;
  c.metric = p.metric;
  c.row = *p.rows[i];
  c.front = c.row.value("front", "");
  c.render_ms = p.points[i].time;
  c.error = p.points[i].error;
  for (std::size_t k : pareto_indices(p.points))
    c.pareto.push_back({{"key", (*p.rows[k])["key"]},
                        {"front", (*p.rows[k]).value("front", "")},
                        {"integrator_params", (*p.rows[k]).value("integrator_params", json::object())},
                        {"render_ms", p.points[k].time},
                        {"error", p.points[k].error}});
  return c;
}

std::string g4(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

double parse_positive(const std::string& text, const std::string& flag) {
  double v = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(v) || v < 0.0)
    throw SweepError(flag + ": expected a number >= 0, got '" + text + "'");
  return v;
}

}  // namespace

AccuracyChoice choose_within_error(const json& results, const std::string& scene, double max_error,
                                   const std::string& front) {
  const Pool p = pool_of(results, scene, front, "--max-error");
  // Along the front, fastest first, errors fall: the first point within the budget is the
  // fastest configuration within it (nothing off the front is faster at no more error).
  for (std::size_t i : pareto_indices(p.points))
    if (p.points[i].error <= max_error) return choice(p, scene, i);
  std::size_t best = 0;
  for (std::size_t i = 1; i < p.points.size(); ++i)
    if (p.points[i].error < p.points[best].error) best = i;
  throw SweepError("--max-error: no configuration of " + scene + " has " + p.metric + " <= " + g4(max_error) +
                   " (smallest: " + g4(p.points[best].error) + ", by " +
                   p.rows[best]->value("integrator_params", json::object()).dump() + ")");
}

AccuracyChoice choose_within_time(const json& results, const std::string& scene, double max_ms,
                                  const std::string& front) {
  const Pool p = pool_of(results, scene, front, "--max-time");
  std::optional<std::size_t> pick;
  for (std::size_t i : pareto_indices(p.points))
    if (p.points[i].time <= max_ms) pick = i;  // later on the front: slower and more accurate
  if (pick) return choice(p, scene, *pick);
  std::size_t fastest = 0;
  for (std::size_t i = 1; i < p.points.size(); ++i)
    if (p.points[i].time < p.points[fastest].time) fastest = i;
  throw SweepError("--max-time: no configuration of " + scene + " renders within " + g4(max_ms) +
                   " ms (fastest: " + g4(p.points[fastest].time) + " ms, by " +
                   p.rows[fastest]->value("integrator_params", json::object()).dump() + ")");
}

json to_json(const AccuracyChoice& c) {
  return {{"scene", c.scene},
          {"front", c.front},
          {"metric", c.metric},
          {"integrator_params", c.row.value("integrator_params", json::object())},
          {"key", c.row["key"]},
          {"render_ms", c.render_ms},
          {"error", c.error},
          {"row", c.row},
          {"pareto", c.pareto}};
}

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
              by_error ? c.metric.c_str() : "time", by_error ? g4(budget).c_str() : (g4(budget) + " ms").c_str());
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

}  // namespace bench
