// Speed/accuracy fronts (harness/fronts.h, harness/accuracy_reference.h, harness/tune_accuracy.h):
// the definition a request expands to, bad input as one line naming what is wrong, a small run
// end to end (errors, Pareto marking, the reference cache, resume, schema), and the accuracy
// tuner honouring its budget.

#include "harness/accuracy_reference.h"
#include "harness/analytic_reference.h"
#include "harness/fronts.h"
#include "cli/fronts_flags.h"
#include "harness/sweep_results.h"
#include "harness/tune_accuracy.h"

#include "scenes_gen/generators.h"
#include "scenes_gen/photon_scenes.h"
#include "integrators/integrators.h"
#include "tracer/image_error.h"
#include "tracer/render.h"

#include "cli_run.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <utility>

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("accelbench_fronts_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

using cli_run::CliRun;

using cli_run::accelbench;

harness::FrontsRequest small_request() {
  harness::FrontsRequest r;
  r.name = "t";
  r.scenes = {harness::parse_scene_item("five")};
  r.groups = {{"max_depth"}, {"spp"}};
  r.values = {{"max_depth", {1, 2, 8}}, {"spp", {1, 4}}};
  r.width = 24;
  r.height = 18;
  r.validate_width = 8;
  r.validate_height = 6;
  r.repetitions = 1;
  r.warmup = 0;
  r.settings.seeds = 3;
  return r;
}

/// Run options writing into dir (`name`.json and `name`.jsonl), references cached in dir/cache, quiet.
std::pair<harness::RunOptions, harness::ReferenceOptions> quiet_options(const fs::path& dir, const std::string& name) {
  harness::RunOptions o;
  o.out_path = (dir / (name + ".json")).string();
  o.jsonl_path = (dir / (name + ".jsonl")).string();
  o.progress = false;
  harness::ReferenceOptions ro;
  ro.cache_dir = (dir / "cache").string();
  ro.validate_width = 8;
  ro.validate_height = 6;
  ro.progress = false;
  return {o, ro};
}

std::string definition_error(const harness::FrontsRequest& r) {
  try {
    harness::fronts_definition(r);
  } catch (const harness::SweepError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(FrontsDefinition, GroupsBecomeIntegratorKnobGroupsWithTheFixedKnobs) {
  harness::FrontsRequest r = small_request();
  r.settings.fixed = {{"min_weight", 0.01}};
  const harness::SweepDefinition d = harness::fronts_definition(r);
  ASSERT_EQ(d.integrator_knobs.size(), 2u);
  EXPECT_EQ(d.integrator_knobs[0].at("max_depth").size(), 3u);
  EXPECT_EQ(d.integrator_knobs[0].at("min_weight"), std::vector<json>{0.01});
  EXPECT_EQ(d.integrator_knobs[1].at("spp").size(), 2u);
  EXPECT_EQ(harness::expand(d).size(), 5u);
  // The default values of a knob come from its row: max depth 1 to 64, log-spaced.
  r.values.erase("max_depth");
  const auto depths = harness::fronts_definition(r).integrator_knobs[0].at("max_depth");
  EXPECT_EQ(depths.front(), 1);
  EXPECT_EQ(depths.back(), 64);
  // Joint: one group, crossed.
  r = small_request();
  r.groups = {{"max_depth", "spp"}};
  EXPECT_EQ(harness::expand(harness::fronts_definition(r)).size(), 6u);
}

TEST(FrontsDefinition, ReferencesDependOnlyOnTheStudiedKnobs) {
  const harness::ReferenceSpec depth = harness::group_reference("whitted", {"max_depth"}, json::object(), 32, 24);
  EXPECT_EQ(depth.params, json({{"max_depth", 64}, {"min_weight", 0}}));
  EXPECT_FALSE(depth.stochastic);
  EXPECT_EQ(depth.check, json({{"max_depth", 48}, {"min_weight", 0}}));
  EXPECT_EQ(harness::group_reference("whitted", {"min_weight"}, json::object(), 32, 24).params, depth.params);
  const harness::ReferenceSpec spp = harness::group_reference("whitted", {"spp"}, {{"max_depth", 5}}, 32, 24);
  EXPECT_EQ(spp.params, json({{"max_depth", 5}, {"spp", 1024}}));  // at the front's own depth
  EXPECT_TRUE(spp.stochastic);
  // The photon knobs' ppm reference is progressive: it estimates its bias from its own stages
  // (passes), of order 1 - alpha, with the estimator asked for, and renders no separate check.
  const harness::ReferenceSpec k = harness::group_reference("photon", {"k"}, json::object(), 32, 24);
  EXPECT_EQ(k.integrator, "ppm");
  EXPECT_TRUE(k.stochastic);
  EXPECT_TRUE(k.check.empty());
  EXPECT_EQ(k.stage_knob, "passes");
  EXPECT_NEAR(k.bias_order, 1.0 / 3.0, 1e-6);
  EXPECT_EQ(k.estimator, harness::ReferenceEstimator::Plain);
  const harness::ReferenceSpec rich = harness::group_reference("photon", {"k"}, json::object(), 32, 24,
                                                               {{"alpha", 0.5}}, harness::ReferenceEstimator::Richardson);
  EXPECT_EQ(rich.estimator, harness::ReferenceEstimator::Richardson);
  EXPECT_NEAR(rich.bias_order, 0.5, 1e-6);
  EXPECT_NE(harness::to_json(rich), harness::to_json(k));  // so the cache keys differ
  EXPECT_TRUE(depth.stage_knob.empty());
}

TEST(FrontsDefinition, BadInputIsOneLineNamingWhatIsWrong) {
  struct Case {
    std::function<void(harness::FrontsRequest&)> edit;
    std::string message;
  };
  const std::vector<Case> cases = {
      {[](auto& r) { r.groups = {{"max_dept"}}; }, "--knobs: unknown knob 'max_dept': integrator whitted has the accuracy knobs max_depth, min_weight, spp"},
      {[](auto& r) { r.values["spp"] = {}; }, "--values: knob 'spp' has an empty range"},
      {[](auto& r) { r.values["min_weight"] = {0.1}; }, "--values: knob 'min_weight' is not among --knobs"},
      {[](auto& r) { r.values["spp"] = {0.5}; }, "--values: whitted: knob 'spp' must be"},
      {[](auto& r) { r.settings.fixed = {{"spp", 2}}; }, "--set: knob 'spp' is both varied (--knobs) and fixed (--set)"},
      {[](auto& r) { r.settings.fixed = {{"colour", 2}}; }, "--set: whitted: unknown knob 'colour'"},
      {[](auto& r) { r.groups = {{"spp"}, {"spp"}}; }, "--knobs: group spp is given twice"},
      {[](auto& r) { r.integrator = "spd"; }, "--knobs: unknown knob 'max_depth': integrator spd has no accuracy knobs"},
      {[](auto& r) { r.structure = "octre"; }, "fronts: /structures/0/name: unknown structure 'octre'"},
  };
  for (const auto& c : cases) {
    harness::FrontsRequest r = small_request();
    c.edit(r);
    const std::string got = definition_error(r);
    EXPECT_EQ(got.rfind(c.message, 0), 0u) << "got: " << got;
    EXPECT_EQ(got.find('\n'), std::string::npos);
  }
  EXPECT_THROW(cli::parse_knob_values_text("", "--values x"), harness::SweepError);
  EXPECT_THROW(cli::parse_knob_values_text("0:10:4", "--values x"), harness::SweepError);
  EXPECT_EQ(cli::parse_knob_values_text("1:64:7", "--values x"), (std::vector<json>{1, 2, 4, 8, 16, 32, 64}));
  // Integers past 2^53 were rounded by llround past the range of long long (found by fuzz_cli).
  try {
    cli::parse_knob_values_text("1:99999999999999999999:3", "--values x");
    ADD_FAILURE() << "an integer range past 2^53 was accepted";
  } catch (const harness::SweepError& e) {
    EXPECT_STREQ(e.what(), "--values x: an integer range LO:HI:N needs HI <= 2^53, got '99999999999999999999'");
  }
  EXPECT_EQ(cli::parse_knob_values_text("0.5,2,true,abc", "--values x"),
            (std::vector<json>{0.5, 2, true, "abc"}));
}

/// Hand-made fronts results: one scene, points (ms, rmse) of two groups.
json hand_made_results() {
  json rows = json::array();
  const std::vector<std::tuple<std::string, double, double>> points = {
      {"max_depth", 10, 0.5}, {"max_depth", 20, 0.2}, {"max_depth", 25, 0.3},  // 25 ms is dominated
      {"max_depth", 40, 0.05}, {"spp", 15, 0.4},      {"spp", 60, 0.01},
      {"spp", 30, 0.2}};  // 30 ms, 0.2: dominated by 20 ms, 0.2
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& [front, ms, err] = points[i];
    rows.push_back({{"key", "k" + std::to_string(i)},
                    {"scene", "s"},
                    {"status", "ok"},
                    {"front", front},
                    {"integrator_params", {{front, int(i)}}},
                    {"render_ms", {{"median", ms}}},
                    {"error", {{"rmse", err}, {"rel_mse", err * err}}},
                    {"reference", {{"floor", {{"rmse", 1e-3}, {"rel_mse", 1e-6}}}}}});
  }
  harness::FrontsSettings s;
  s.groups = {{"max_depth"}, {"spp"}};
  return {{"sweep", {{"fronts", harness::to_json(s)}}}, {"rows", rows}};
}

TEST(AccuracyTune, MaxErrorHonoursTheBudgetAndNothingFasterMeetsIt) {
  const json results = hand_made_results();
  for (double budget : {0.5, 0.45, 0.3, 0.2, 0.1, 0.05, 0.01}) {
    const harness::AccuracyChoice c = harness::choose_within_error(results, "s", budget);
    EXPECT_LE(c.error, budget);
    for (const json& row : results["rows"])
      if (row["render_ms"]["median"].get<double>() < c.render_ms) {
        EXPECT_GT(row["error"]["rmse"].get<double>(), budget) << "faster and within budget: " << row["key"];
      }
    bool on_front = false;
    for (const json& p : c.pareto) on_front = on_front || p["key"] == c.row["key"];
    EXPECT_TRUE(on_front);
  }
  EXPECT_EQ(harness::choose_within_error(results, "s", 0.2).row["key"], "k1");
  EXPECT_EQ(harness::choose_within_error(results, "s", 0.2, "spp").row["key"], "k6");
  try {
    harness::choose_within_error(results, "s", 0.001);
    ADD_FAILURE() << "no error for an impossible budget";
  } catch (const harness::SweepError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("--max-error: no configuration of s has rmse <= 0.001 (smallest: 0.01", 0), 0u)
        << e.what();
  }
}

// The tuner refuses a budget it cannot certify: below every reference's floor, one line naming
// the floor; rows whose own reference's floor lies above the budget are not chosen.
TEST(AccuracyTune, MaxErrorBelowTheReferenceFloorIsRefused) {
  json results = hand_made_results();
  try {
    harness::choose_within_error(results, "s", 0.0005);
    ADD_FAILURE() << "no error for a budget below the floor";
  } catch (const harness::SweepError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--max-error: cannot certify an error below the reference floor 0.001 (rmse of s's references)");
  }
  // The max_depth front's reference is coarse (floor 0.1): within 0.06, its 40 ms row (error
  // 0.05) cannot be certified, so the slower spp row (60 ms, 0.01, floor 0.001) is chosen.
  EXPECT_EQ(harness::choose_within_error(results, "s", 0.06).row["key"], "k3");
  for (json& row : results["rows"])
    if (row["front"] == "max_depth") row["reference"]["floor"]["rmse"] = 0.1;
  EXPECT_EQ(harness::choose_within_error(results, "s", 0.06).row["key"], "k5");
}

TEST(AccuracyTune, MaxTimeGivesTheMostAccurateWithinIt) {
  const json results = hand_made_results();
  for (double budget : {10.0, 19.0, 20.0, 39.0, 45.0, 100.0}) {
    const harness::AccuracyChoice c = harness::choose_within_time(results, "s", budget);
    EXPECT_LE(c.render_ms, budget);
    for (const json& row : results["rows"])
      if (row["render_ms"]["median"].get<double>() <= budget) {
        EXPECT_GE(row["error"]["rmse"].get<double>(), c.error);
      }
  }
  EXPECT_THROW(harness::choose_within_time(results, "s", 5.0), harness::SweepError);
  EXPECT_THROW(harness::choose_within_time(results, "nope", 50.0), harness::SweepError);
}

TEST(Fronts, AnnotationMarksExactlyTheNonDominatedRows) {
  json results = hand_made_results();
  harness::annotate_fronts(results);
  std::vector<bool> on;
  for (const json& row : results["rows"]) on.push_back(row["on_front"].get<bool>());
  // Per group: max_depth {10,.5} {20,.2} {40,.05} on, {25,.3} off; spp {15,.4} {60,.01} on,
  // {30,.2} on within its own group.
  EXPECT_EQ(on, (std::vector<bool>{true, true, false, true, true, true, true}));
  ASSERT_EQ(results["fronts"].size(), 2u);
  EXPECT_EQ(results["fronts"][0]["smallest_error"], 0.05);
  EXPECT_DOUBLE_EQ(results["fronts"][0]["floor_ratio"].get<double>(), 50.0);
}

/// Hand-made fronts results of one spp front whose reference has floor 0.01 RMSE (1e-4 relative
/// MSE): rows (key, ms, rmse, the seeds' rmse).
json floor_results(const std::vector<std::tuple<std::string, double, double, std::vector<double>>>& points) {
  json rows = json::array();
  for (const auto& [key, ms, err, seeds] : points) {
    json row = {{"key", key},
                {"scene", "s"},
                {"status", "ok"},
                {"front", "spp"},
                {"integrator_params", {{"spp", int(ms)}}},
                {"render_ms", {{"median", ms}}},
                {"error", {{"rmse", err}, {"rel_mse", err * err}}},
                {"reference", {{"floor", {{"rmse", 0.01}, {"rel_mse", 1e-4}}}}}};
    if (!seeds.empty()) {
      json rel = json::array();
      for (double e : seeds) rel.push_back(e * e);
      row["seed_errors"] = {{"rmse", seeds}, {"rel_mse", rel}};
    }
    rows.push_back(row);
  }
  harness::FrontsSettings s;
  s.groups = {{"spp"}};
  return {{"sweep", {{"fronts", harness::to_json(s)}}}, {"rows", rows}};
}

// Every row gets its error's interval (the seeds' spread widened by the floor) and whether it is
// resolved; an unresolved row does not push a resolved one off the front.
TEST(Fronts, RowsCarryAnErrorIntervalAndUnresolvedRowsDoNotBeatResolvedOnes) {
  json results = floor_results({
      {"far", 10, 0.5, {}},                                 // resolved: [0.49, 0.51]
      {"noisy", 20, 0.015, {0.015, 0.02, 0.012, 0.018}},   // unresolved: [0.002, 0.03]
      {"resolved", 30, 0.05, {0.05, 0.045, 0.055, 0.05}},  // resolved: [0.035, 0.065]
      {"at_floor", 40, 0.01, {}},                           // unresolved: [0, 0.02]
      {"below", 50, 0.005, {}},                             // unresolved: [0, 0.015]
  });
  harness::annotate_fronts(results);
  std::map<std::string, json> row;
  for (const json& r : results["rows"]) row[r["key"]] = r;
  auto near = [](const json& interval, double lo, double hi) {
    EXPECT_NEAR(interval[0].get<double>(), lo, 1e-12) << interval;
    EXPECT_NEAR(interval[1].get<double>(), hi, 1e-12) << interval;
  };
  near(row["far"]["error_interval"], 0.49, 0.51);
  near(row["noisy"]["error_interval"], 0.002, 0.03);
  near(row["resolved"]["error_interval"], 0.035, 0.065);
  near(row["at_floor"]["error_interval"], 0.0, 0.02);
  near(row["below"]["error_interval"], 0.0, 0.015);
  EXPECT_TRUE(row["far"]["resolved"].get<bool>());
  EXPECT_FALSE(row["noisy"]["resolved"].get<bool>());
  EXPECT_TRUE(row["resolved"]["resolved"].get<bool>());
  EXPECT_FALSE(row["at_floor"]["resolved"].get<bool>());
  EXPECT_FALSE(row["below"]["resolved"].get<bool>());
  // The unresolved 20 ms row is faster and measured more accurate than the resolved 30 ms one,
  // which the plain rule would drop; it stays. The unresolved rows beat each other as before.
  EXPECT_TRUE(row["resolved"]["on_front"].get<bool>());
  EXPECT_TRUE(row["noisy"]["on_front"].get<bool>());
  EXPECT_TRUE(row["at_floor"]["on_front"].get<bool>());
  EXPECT_TRUE(row["below"]["on_front"].get<bool>());
  const json& front = results["fronts"][0];
  EXPECT_EQ(front["unresolved"], 3);
  EXPECT_DOUBLE_EQ(front["floor_ratio"].get<double>(), 0.5);  // 0.005 over 0.01
  ASSERT_EQ(front["pareto"].size(), 5u);
  EXPECT_EQ(front["pareto"][2]["key"], "resolved");
  EXPECT_EQ(front["pareto"][2]["resolved"], true);
  EXPECT_EQ(front["pareto"][1]["resolved"], false);
  // Annotating again (as merge does) gives the same document.
  json again = results;
  harness::annotate_fronts(again);
  EXPECT_EQ(again, results);

  // In relative MSE the floor adds in the square roots: 0.015^2 with the seeds' spread gives
  // [(0.012 - 0.01)^2, (0.02 + 0.01)^2], the same rows unresolved.
  results["sweep"]["fronts"]["metric"] = "rel_mse";
  harness::annotate_fronts(results);
  for (const json& r : results["rows"]) row[r["key"]] = r;
  near(row["noisy"]["error_interval"], 0.002 * 0.002, 0.03 * 0.03);
  near(row["far"]["error_interval"], 0.49 * 0.49, 0.51 * 0.51);
  EXPECT_FALSE(row["noisy"]["resolved"].get<bool>());
  EXPECT_TRUE(row["resolved"]["resolved"].get<bool>());
  EXPECT_EQ(results["fronts"][0]["unresolved"], 3);
}

TEST(Fronts, RunEndToEndWithCachedReferencesAndResume) {
  const fs::path dir = temp_dir("run");
  const harness::SweepDefinition d = harness::fronts_definition(small_request());
  auto [o, ro] = quiet_options(dir, "t");
  const harness::FrontsSummary first = harness::run_fronts(d, o, ro);
  EXPECT_TRUE(first.sweep.complete);
  EXPECT_EQ(first.references_made, 2);  // one per group
  EXPECT_EQ(first.references_cached, 0);
  const json results = harness::read_results_file(o.out_path);
  ASSERT_EQ(results["rows"].size(), 5u);
  for (const json& row : results["rows"]) {
    ASSERT_EQ(row["status"], "ok") << row.dump();
    ASSERT_TRUE(row.contains("error") && row.contains("on_front"));
    EXPECT_TRUE(row["error"]["rmse"].is_number());
    if (row["front"] == "spp") {
      // One sample per pixel sits at the pixel centre whatever the seed: all of its error is
      // bias; four jittered samples vary with the seed.
      ASSERT_TRUE(row.contains("bias_variance"));
      EXPECT_EQ(row["bias_variance"]["stochastic"], row["integrator_params"]["spp"] == 4);
    } else {
      EXPECT_FALSE(row.contains("bias_variance"));  // a deterministic reference: no split
    }
  }
  // Every row carries its error's interval and whether the reference resolves it; the spp rows
  // that vary with the seed carry each seed's error, the timed image's first.
  std::size_t unresolved = 0;
  for (const json& row : results["rows"]) {
    ASSERT_TRUE(row.contains("error_interval") && row.contains("resolved")) << row.dump();
    const double err = row["error"]["rmse"], floor = row["reference"]["floor"]["rmse"];
    const double lo = row["error_interval"][0], hi = row["error_interval"][1];
    EXPECT_LE(lo, err);
    EXPECT_GE(hi, err + floor * (1 - 1e-12));
    EXPECT_EQ(row["resolved"].get<bool>(), lo > floor);
    unresolved += !row["resolved"].get<bool>();
    const bool seeded = row.contains("bias_variance") && row["bias_variance"]["stochastic"].get<bool>();
    EXPECT_EQ(row.contains("seed_errors"), seeded) << row.dump();
    if (seeded) {
      ASSERT_EQ(row["seed_errors"]["rmse"].size(), 3u);  // --seeds 3
      EXPECT_EQ(row["seed_errors"]["rmse"][0], row["error"]["rmse"]);
      EXPECT_EQ(row["seed_errors"]["rel_mse"][0], row["error"]["rel_mse"]);
    }
  }
  std::size_t counted = 0;
  for (const json& f : results["fronts"]) counted += f["unresolved"].get<std::size_t>();
  EXPECT_EQ(counted, unresolved);
  // Depth 1 is the least accurate and fastest; the error falls with depth on five's glass.
  std::map<int, double> by_depth;
  for (const json& row : results["rows"])
    if (row["front"] == "max_depth") by_depth[row["integrator_params"]["max_depth"]] = row["error"]["rmse"];
  EXPECT_GT(by_depth[1], by_depth[2]);
  EXPECT_GT(by_depth[2], by_depth[8]);
  ASSERT_EQ(results["fronts"].size(), 2u);
  for (const json& f : results["fronts"]) {
    EXPECT_GE(f["pareto"].size(), 1u);
    EXPECT_TRUE(f["floor"].is_number());
  }
  // The references are cached: a fresh run reads them and finds the same errors.
  fs::remove(o.jsonl_path);
  const harness::FrontsSummary second = harness::run_fronts(d, o, ro);
  EXPECT_EQ(second.references_made, 0);
  EXPECT_EQ(second.references_cached, 2);
  const json again = harness::read_results_file(o.out_path);
  for (std::size_t i = 0; i < 5; ++i)
    EXPECT_EQ(again["rows"][i]["error"], results["rows"][i]["error"]) << i;
  // Resume: nothing left to measure.
  o.resume = true;
  const harness::FrontsSummary resumed = harness::run_fronts(d, o, ro);
  EXPECT_EQ(resumed.sweep.measured, 0u);
  EXPECT_EQ(harness::read_results_file(o.out_path)["rows"].size(), 5u);
  // The results file follows the schema.
  std::ofstream(dir / "validate.py") << "import json, sys\nimport jsonschema\n"
                                        "schema = json.load(open(sys.argv[1]))\n"
                                        "errors = list(jsonschema.Draft202012Validator(schema).iter_errors(json.load(open(sys.argv[2]))))\n"
                                        "for e in errors[:5]: print(list(e.absolute_path), e.message[:300])\n"
                                        "sys.exit(1 if errors else 0)\n";
  const std::string cmd = std::string(ACCELBENCH_PYTHON) + " " + (dir / "validate.py").string() + " " +
                          ACCELBENCH_SOURCE_DIR "/results/schema/results.schema.json " + o.out_path;
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  fs::remove_all(dir);
}

// Float against double: the reference is the double render, so double's error is exactly 0 and
// float's is its (small, non-zero) distance from it; both are on the front (double is slower).
TEST(Fronts, PrecisionFrontMeasuresFloatAgainstTheDoubleReference) {
  const fs::path dir = temp_dir("precision");
  harness::FrontsRequest r = small_request();
  r.scenes = {harness::parse_scene_item("refraction")};
  r.groups = {{"precision"}};
  r.values.clear();
  const harness::SweepDefinition d = harness::fronts_definition(r);
  const auto [o, ro] = quiet_options(dir, "p");
  harness::run_fronts(d, o, ro);
  const json results = harness::read_results_file(o.out_path);
  ASSERT_EQ(results["rows"].size(), 2u);
  std::map<std::string, double> error;
  for (const json& row : results["rows"]) {
    ASSERT_EQ(row["status"], "ok") << row.dump();
    error[row["integrator_params"]["precision"]] = row["error"]["rmse"];
  }
  EXPECT_EQ(error.at("double"), 0.0);
  EXPECT_GT(error.at("float"), 0.0);
  EXPECT_LT(error.at("float"), 1e-3);  // float rounding, not a different picture
  ASSERT_EQ(results["fronts"].size(), 1u);
  EXPECT_EQ(results["fronts"][0]["reference"]["params"]["precision"], "double");
  EXPECT_EQ(results["fronts"][0]["floor"], 0.0);
  // The double row is the reference itself: its error (0) cannot be told from the reference's,
  // so it is unresolved; float's small error is resolved against a floor of 0.
  for (const json& row : results["rows"])
    EXPECT_EQ(row["resolved"].get<bool>(), row["integrator_params"]["precision"] == "float") << row.dump();
  EXPECT_EQ(results["fronts"][0]["unresolved"], 1);
  fs::remove_all(dir);
}

TEST(AccuracyReference, HalvesGiveTheNoiseAndTheCacheKeyFollowsTheScene) {
  scenes_gen::GenOptions g;
  tracer::Scene scene = scenes_gen::generate("five", g);
  const accel::AnyAccel built = accel::make_accel("bvh", json::object(), scene.geometry.primitive_bounds());
  harness::ReferenceSpec spec;
  spec.integrator = "whitted";
  spec.params = {{"spp", 16}};
  spec.stochastic = true;
  spec.width = 24;
  spec.height = 18;
  harness::ReferenceOptions ro;
  ro.progress = false;
  const harness::AccuracyReference r = harness::obtain_reference(scene, built, spec, ro);
  EXPECT_GT(r.floor.noise_rmse, 0.0);
  EXPECT_EQ(r.floor.truncation_rmse, 0.0);
  EXPECT_DOUBLE_EQ(r.floor.rmse, r.floor.noise_rmse);
  // Independently: the mean of the halves is the reference, and half their RMSE is the noise.
  tracer::RenderOptions o;
  o.width = 24;
  o.height = 18;
  const auto a = tracer::render(scene, built, o, tracer::whitted_integrator(), {{"spp", 16}, {"seed", harness::kReferenceSeedA}});
  const auto b = tracer::render(scene, built, o, tracer::whitted_integrator(), {{"spp", 16}, {"seed", harness::kReferenceSeedB}});
  EXPECT_DOUBLE_EQ(r.floor.noise_rmse, tracer::image_error(a.image, b.image).rmse / 2);
  const tracer::Image halves[2] = {a.image, b.image};
  EXPECT_EQ(r.image, tracer::mean_image(halves));
  // A 4x finer reference has a smaller floor.
  spec.params["spp"] = 64;
  EXPECT_LT(harness::obtain_reference(scene, built, spec, ro).floor.noise_rmse, r.floor.noise_rmse);
  // The key changes with the scene and the spec, not with the order knobs were written in.
  const std::string key = harness::reference_key(scene, spec);
  spec.params = {{"spp", 64}};
  EXPECT_EQ(harness::reference_key(scene, spec), key);
  scene.lights[0].power_w *= 2;
  EXPECT_NE(harness::reference_key(scene, spec), key);
}

// The stopping rule of progressive references: level after level with 8x the passes until the
// floor reaches the target, or the next level would pass the time limit; each level cached.
TEST(AccuracyReference, ProgressiveLevelsStopAtTheFloorTargetOrTheTimeLimit) {
  scenes_gen::GenOptions g;
  const tracer::Scene scene = scenes_gen::generate("glass_caustic", g);
  const accel::AnyAccel built = accel::make_accel("bvh", json::object(), scene.geometry.primitive_bounds());
  harness::ReferenceSpec spec =
      harness::group_reference("photon", {"k"}, json::object(), 24, 18, {{"passes", 8}, {"photons_per_pass", 2000}});
  const fs::path dir = fs::temp_directory_path() / ("accelbench_levels_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  harness::ReferenceOptions ro;
  ro.progress = false;
  ro.cache_dir = dir.string();
  ro.threads = 2;

  // No target: the recipe's passes only. The floor holds the noise and the stages' bias bound.
  const harness::AccuracyReference base = harness::obtain_reference(scene, built, spec, ro);
  EXPECT_TRUE(base.stopping.is_null());
  EXPECT_GT(base.floor.noise_rmse, 0.0);
  EXPECT_GE(base.floor.bias_rmse, base.floor.bias_rmse_estimate);
  EXPECT_EQ(base.floor.truncation_rmse, 0.0);
  EXPECT_NEAR(base.floor.rmse * base.floor.rmse,
              base.floor.noise_rmse * base.floor.noise_rmse + base.floor.bias_rmse * base.floor.bias_rmse, 1e-12);

  // A target the first level meets: it stops there, read from the cache.
  ro.floor_target = base.floor.rmse * 1.01;
  const harness::AccuracyReference met = harness::obtain_reference(scene, built, spec, ro);
  EXPECT_EQ(met.stopping["stopped_by"], "floor");
  EXPECT_EQ(met.stopping["levels"].size(), 1u);
  EXPECT_TRUE(met.from_cache);
  EXPECT_EQ(met.image, base.image);

  // A lower target: 8x and 64x the passes, until the floor meets it.
  ro.floor_target = base.floor.rmse * 0.6;
  const harness::AccuracyReference deeper = harness::obtain_reference(scene, built, spec, ro);
  EXPECT_EQ(deeper.stopping["stopped_by"], "floor") << deeper.stopping.dump();
  ASSERT_GE(deeper.stopping["levels"].size(), 2u);
  EXPECT_EQ(deeper.stopping["levels"][1]["stages"], 64);
  EXPECT_LE(deeper.floor.rmse, ro.floor_target);
  EXPECT_EQ(deeper.spec.params["passes"], deeper.stopping["levels"].back()["stages"]);
  EXPECT_EQ(deeper.stopping["levels"][0]["from_cache"], true);

  // No time for another level: it stops at the first and says so.
  ro.floor_target = base.floor.rmse * 1e-6;
  ro.time_limit_s = 0.0;
  const harness::AccuracyReference limited = harness::obtain_reference(scene, built, spec, ro);
  EXPECT_EQ(limited.stopping["stopped_by"], "time_limit");
  EXPECT_EQ(limited.stopping["levels"].size(), 1u);

  // Richardson needs two checkpoints of 8x below the passes.
  spec.estimator = harness::ReferenceEstimator::Richardson;
  ro.floor_target = 0.0;
  try {
    harness::obtain_reference(scene, built, spec, ro);
    ADD_FAILURE() << "8 passes cannot make a richardson reference";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "reference: a richardson reference needs passes divisible by 64, got 8");
  }
  spec.params["passes"] = 64;
  const harness::AccuracyReference rich = harness::obtain_reference(scene, built, spec, ro);
  EXPECT_GT(rich.floor.noise_rmse, 0.0);
  EXPECT_NE(rich.key, base.key);
  // Plain and Richardson at the same passes share their halves' renders: the plain one at 64
  // passes was rendered as the stopping rule's second level, and Richardson's halves are those.
  EXPECT_TRUE(rich.from_cache);
  spec.estimator = harness::ReferenceEstimator::Plain;
  const harness::AccuracyReference plain64 = harness::obtain_reference(scene, built, spec, ro);
  EXPECT_TRUE(plain64.from_cache);
  EXPECT_NE(plain64.image, rich.image);
  EXPECT_GT(rich.floor.noise_rmse, plain64.floor.noise_rmse);  // 2 L_N - L_N/8 weighs the noisier stage in
  // --refresh-reference renders them again, to the same pixels.
  ro.refresh = true;
  const harness::AccuracyReference again = harness::obtain_reference(scene, built, spec, ro);
  EXPECT_FALSE(again.from_cache);
  EXPECT_EQ(again.image, plain64.image);
  fs::remove_all(dir);
}

// The furnace has a closed form, and a consistent reference (ppm) converges to it: it is the
// reference there, with floor 0. Scenes that only look like it are rendered.
TEST(AccuracyReference, TheFurnaceIsItsOwnClosedForm) {
  tracer::Scene scene = scenes_gen::make_furnace_scene(2.0f, 0.6f, 50.0f);
  const accel::AnyAccel built = accel::make_accel("bvh", json::object(), scene.geometry.primitive_bounds());
  const harness::ReferenceSpec spec =
      harness::group_reference("photon", {"global_photons"}, json::object(), 16, 12, {{"passes", 8}, {"photons_per_pass", 4000}});
  harness::ReferenceOptions ro;
  ro.progress = false;
  const harness::AccuracyReference r = harness::obtain_reference(scene, built, spec, ro);
  EXPECT_EQ(r.analytic, "furnace");
  EXPECT_EQ(r.floor.rmse, 0.0);
  const double truth = 0.6 * 50.0 / (4.0 * M_PI * M_PI * 4.0 * 0.4);
  ASSERT_EQ(r.image.width(), 16);
  for (const auto& p : r.image.pixels()) EXPECT_NEAR(p.x, truth, 1e-6 * truth);
  // ppm itself lands on it within a few percent at this budget.
  tracer::RenderOptions o;
  o.width = 16;
  o.height = 12;
  json params = spec.params;
  params["seed"] = 3;
  params["passes"] = 64;
  const tracer::Image ppm = tracer::render(scene, built, o, *integrators::find("ppm"), params).image;
  EXPECT_LT(tracer::image_error(ppm, r.image).rmse, 0.05 * truth);
  // Whitted's references stay rendered: its recursion stops at the first diffuse bounce.
  EXPECT_TRUE(harness::obtain_reference(scene, built,
                                        harness::group_reference("whitted", {"spp"}, json::object(), 8, 6, {{"spp", 4}}), ro)
                  .analytic.empty());
  // A light off the centre, or the camera outside, is no furnace.
  scene.lights[0].position.x = 0.1f;
  EXPECT_FALSE(harness::furnace_radiance(scene));
  scene.lights[0].position.x = 0.0f;
  EXPECT_TRUE(harness::furnace_radiance(scene));
  scene.camera.position.z = 3.0f;
  EXPECT_FALSE(harness::furnace_radiance(scene));
}

TEST(FrontsCli, BadInputGivesOneLine) {
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {"fronts five --knobs depth --no-cache", "accelbench: --knobs: unknown knob 'depth'"},
      {"fronts five --knobs spp --values spp= --no-cache", "accelbench: --values spp: empty range"},
      {"fronts five --knobs spp --values spp=0:4:3 --no-cache", "accelbench: --values spp: a log-spaced range"},
      {"fronts five --knobs spp --metric l2 --no-cache", "accelbench: --metric: must be rmse or rel_mse"},
      {"tune five --max-error 0.01", "accelbench: --max-error/--max-time: give --fronts FILE or --knobs LIST"},
      {"fronts glass_caustic --integrator photon --knobs k --reference-set passes=100 --no-cache",
       "accelbench: --reference-set: a plain ppm reference needs passes divisible by 8 (its checkpoints), got 100"},
      {"fronts glass_caustic --integrator photon --knobs k --reference-set passes=8 --estimator richardson --no-cache",
       "accelbench: --reference-set: a richardson ppm reference needs passes divisible by 64 (its checkpoints), got 8"},
      {"fronts five --knobs spp --estimator linear --no-cache",
       "accelbench: --estimator: estimator must be plain or richardson, got 'linear'"},
      {"fronts five --knobs spp --floor-target-from /nonexistent/f.json --no-cache",
       "accelbench: --floor-target-from /nonexistent/f.json: "},
      {"fronts five --knobs spp --floor-target-from " ACCELBENCH_SOURCE_DIR "/results/fronts-five.json --metric rel_mse --no-cache",
       "accelbench: --floor-target-from " ACCELBENCH_SOURCE_DIR "/results/fronts-five.json: its fronts are in rmse, not --metric rel_mse"},
      // 100,000 nested brackets: a string to the integrator, never parsed as JSON.
      {"fronts five --knobs spp --values spp=" + std::string(100000, '[') + " --no-cache",
       "accelbench: --values: whitted: knob 'spp' must be an integer"},
  };
  for (const auto& c : cases) {
    const CliRun run = accelbench(c.args);
    EXPECT_NE(run.status, 0) << c.args;
    EXPECT_EQ(run.output.rfind(c.message, 0), 0u) << c.args << "\n got: " << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
  }
}

TEST(FrontsCli, TuneAnswersFromAFrontsFileOrSaysWhichBudgetNothingMeets) {
  const fs::path dir = temp_dir("cli");
  const std::string out = (dir / "f.json").string();
  const CliRun fronts = accelbench("fronts five --knobs max_depth --values max_depth=1,2,8 --resolution 24x18 "
                                   "--validate-resolution 8x6 --repetitions 1 --warmup 0 --seeds 1 --quiet --cache " +
                                   (dir / "cache").string() + " --out " + out);
  ASSERT_EQ(fronts.status, 0) << fronts.output;
  EXPECT_NE(fronts.output.find("front max_depth"), std::string::npos) << fronts.output;
  const CliRun ok = accelbench("tune five --max-error 1e9 --fronts " + out + " --json " + (dir / "c.json").string());
  ASSERT_EQ(ok.status, 0) << ok.output;
  EXPECT_NE(ok.output.find("<- chosen"), std::string::npos) << ok.output;
  std::ifstream in(dir / "c.json");
  const json choice = json::parse(in);
  // Anything meets a huge budget: the answer is the fastest row measured.
  std::ifstream rin(out);
  const json measured = json::parse(rin);
  double fastest = 1e300;
  std::string fastest_key;
  for (const json& row : measured["rows"])
    if (row["render_ms"]["median"].get<double>() < fastest) {
      fastest = row["render_ms"]["median"];
      fastest_key = row["key"];
    }
  EXPECT_EQ(choice["key"], fastest_key);
  // A budget of 0 is below the reference's floor when the floor is above 0 (then the tuner
  // cannot certify it), else no configuration meets it; one line either way.
  const double floor = measured["rows"][0]["reference"]["floor"]["rmse"].get<double>();
  const CliRun none = accelbench("tune five --max-error 0 --fronts " + out);
  EXPECT_NE(none.status, 0);
  EXPECT_EQ(none.output.rfind(floor > 0.0 ? "accelbench: --max-error: cannot certify an error below the reference floor "
                                          : "accelbench: --max-error: no configuration of five has rmse <= 0 (smallest: ",
                              0),
            0u)
      << none.output;
  EXPECT_EQ(std::count(none.output.begin(), none.output.end(), '\n'), 1) << none.output;
  fs::remove_all(dir);
}

}  // namespace
