#include "harness/tune_accuracy.h"

#include "harness/fronts.h"
#include "harness/pareto.h"
#include "harness/sweep_definition.h"
#include "harness/sweep_results.h"

#include <algorithm>
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
  /// Per row, the floor of its reference in `metric`: the error the reference itself may carry,
  /// below which a row's error cannot be told from the reference's (0 when not recorded).
  std::vector<double> floors;
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
    const json floor = row.contains("reference") ? row["reference"].value("floor", json::object()) : json::object();
    p.floors.push_back(floor.contains(p.metric) && floor[p.metric].is_number() ? floor[p.metric].get<double>() : 0.0);
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
  // A budget below every reference's floor cannot be certified: the measured errors are not
  // known to that precision. Rows whose own reference's floor lies above the budget are left
  // out for the same reason.
  const double lowest_floor = *std::min_element(p.floors.begin(), p.floors.end());
  if (max_error < lowest_floor)
    throw SweepError("--max-error: cannot certify an error below the reference floor " + four_significant(lowest_floor) +
                     " (" + p.metric + " of " + scene + "'s references)");
  // Along the front, fastest first, errors fall: the first point within the budget is the
  // fastest configuration within it (nothing off the front is faster at no more error).
  for (std::size_t i : pareto_indices(p.points))
    if (p.points[i].error <= max_error && p.floors[i] <= max_error) return choice(p, scene, i);
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
