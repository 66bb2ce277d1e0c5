#include "harness/tune_accuracy.h"

#include "harness/fronts.h"
#include "harness/pareto.h"
#include "harness/sweep_definition.h"
#include "harness/sweep_results.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <vector>

namespace harness {

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

}  // namespace

std::string four_significant(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

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
  throw SweepError("--max-error: no configuration of " + scene + " has " + p.metric + " <= " + four_significant(max_error) +
                   " (smallest: " + four_significant(p.points[best].error) + ", by " +
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
  throw SweepError("--max-time: no configuration of " + scene + " renders within " + four_significant(max_ms) +
                   " ms (fastest: " + four_significant(p.points[fastest].time) + " ms, by " +
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

}  // namespace harness
