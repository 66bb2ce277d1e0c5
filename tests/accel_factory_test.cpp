// The factory: names, knob validation with one-line errors, exact parameters of every build,
// statistics sanity, and the `auto` selection.

#include "accel/accel.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using accel::Aabb;
using accel::Vec3;
using nlohmann::json;

std::vector<Aabb> row_of_boxes(int n) {
  std::vector<Aabb> boxes;
  for (int i = 0; i < n; ++i) boxes.push_back({Vec3(float(i), 0.0f, 0.0f), Vec3(float(i) + 0.5f, 1.0f, 1.0f)});
  return boxes;
}

std::string factory_error(std::string_view name, const json& params, int prims = 10) {
  const auto boxes = row_of_boxes(prims);
  try {
    accel::make_accel(name, params, boxes);
  } catch (const knobs::ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(AccelFactory, NamesListEveryStructure) {
  const std::vector<std::string> names = accel::accel_names();
  for (const char* want : {"naive", "bvh", "embree", "auto"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
  EXPECT_FALSE(accel::accel_built("kdtre"));
  EXPECT_TRUE(accel::accel_built("bvh"));
}

TEST(AccelFactory, UnknownNameListsValidOnes) {
  std::string valid;
  for (const std::string& n : accel::accel_names()) valid += (valid.empty() ? "" : ", ") + n;
  EXPECT_EQ(factory_error("kdtre", nullptr), "unknown structure 'kdtre' (valid: " + valid + ")");
}

TEST(AccelFactory, NaiveRejectsAnyKnob) {
  EXPECT_EQ(factory_error("naive", {{"max_depth", 3}}), "naive: unknown knob 'max_depth' (it has no knobs)");
}

TEST(AccelFactory, BadKnobsNameTheKey) {
  EXPECT_EQ(factory_error("bvh", {{"max_dept", 3}}),
            "bvh: unknown knob 'max_dept' (its knobs: bins, max_leaf_size, max_depth, traversal_cost, build_threads, "
            "spatial_split_budget)");
  EXPECT_EQ(factory_error("bvh", {{"max_depth", "3"}}), "bvh: knob 'max_depth' must be an integer, got \"3\"");
  EXPECT_EQ(factory_error("bvh", {{"max_depth", 65}}), "bvh: knob 'max_depth' must be in [0, 64], got 65");
  EXPECT_EQ(factory_error("bvh", {{"max_depth", -1}}), "bvh: knob 'max_depth' must be in [0, 64], got -1");
  EXPECT_EQ(factory_error("bvh", {{"max_leaf_size", 0}}), "bvh: knob 'max_leaf_size' must be in [1, 255], got 0");
  EXPECT_EQ(factory_error("bvh", {{"bins", 4}}), "bvh: knob 'bins' must be in [8, 256], got 4");
  EXPECT_EQ(factory_error("bvh", {{"max_leaf_size", 2.5}}), "bvh: knob 'max_leaf_size' must be an integer, got 2.5");
  EXPECT_EQ(factory_error("bvh", json::array({1})), "bvh: knobs must be a JSON object, got [1]");
  EXPECT_EQ(factory_error("auto", {{"naive_max_prims", true}}), "auto: knob 'naive_max_prims' must be an integer, got true");
  // The knobs of embree are known (and checked) even in a build without Embree.
  EXPECT_EQ(factory_error("embree", {{"build_quality", "low"}}),
            "embree: knob 'build_quality' must be one of medium|high, got \"low\"");
  EXPECT_EQ(factory_error("embree", {{"robust", 1}}), "embree: knob 'robust' must be true or false, got 1");
  if (!accel::accel_built("embree")) {
    EXPECT_EQ(factory_error("embree", nullptr), "embree: not built (Embree 3 was not found; run scripts/setup)");
  }
}

TEST(AccelFactory, ParamsSpellOutEveryKnob) {
  const auto boxes = row_of_boxes(100);
  const accel::AnyAccel bvh = accel::make_accel("bvh", {{"max_leaf_size", 2}}, boxes);
  EXPECT_EQ(accel::name_of(bvh), "bvh");
  EXPECT_EQ(accel::params_of(bvh),
            json({{"bins", 16},
                  {"max_leaf_size", 2},
                  {"max_depth", 64},
                  {"traversal_cost", 3.0},
                  {"build_threads", 1},
                  {"spatial_split_budget", 0.0}}));
  // Every knob reported can be fed back and gives the same parameters.
  for (const std::string& name : accel::accel_names()) {
    if (!accel::accel_built(name) || accel::find_structure(name)->selector) continue;
    const accel::AnyAccel a = accel::make_accel(name, nullptr, boxes);
    EXPECT_EQ(accel::name_of(a), name);
    const json p = accel::params_of(a);
    EXPECT_EQ(accel::params_of(accel::make_accel(name, p, boxes)), p) << name;
  }
}

TEST(AccelFactory, NaiveStatisticsAndNoNodesVisited) {
  const auto boxes = row_of_boxes(50);
  const accel::AnyAccel a = accel::make_accel("naive", nullptr, boxes);
  EXPECT_EQ(accel::stats_of(a).nodes, 0u);
  accel::TraversalCounters c;
  accel::Ray ray;
  int calls = 0;
  std::get<accel::Naive>(a).intersect<true>(ray, [&](std::uint32_t, accel::Ray&) { return ++calls, false; }, &c);
  EXPECT_EQ(c.nodes_visited, 0u);
  EXPECT_EQ(c.prims_tested, 50u);
  EXPECT_EQ(calls, 50);
}

TEST(AccelFactory, BvhHugeLeafIsOneLeafWithEverything) {
  const auto boxes = row_of_boxes(200);
  for (const json& knobs : {json{{"max_depth", 0}}, json{{"max_leaf_size", 255}, {"traversal_cost", 1000}}}) {
    const accel::BuildStats s = accel::stats_of(accel::make_accel("bvh", knobs, boxes));
    EXPECT_EQ(s.nodes, 1u) << knobs;
    EXPECT_EQ(s.leaves, 1u) << knobs;
    EXPECT_EQ(s.max_leaf_prims, 200u) << knobs;
  }
}

TEST(AccelFactory, AutoPicksNaiveForFewPrimitivesAndSaysSo) {
  const accel::AnyAccel few = accel::make_accel("auto", nullptr, row_of_boxes(3));
  EXPECT_EQ(accel::name_of(few), "naive");
  EXPECT_TRUE(std::holds_alternative<accel::Naive>(few));
  const json p = accel::params_of(few);
  EXPECT_EQ(p.at("selected_by").at("structure"), "auto");
  EXPECT_EQ(p.at("selected_by").at("params").at("naive_max_prims"), accel::AutoParams{}.naive_max_prims);
  EXPECT_EQ(few.selected_by, p.at("selected_by"));

  const accel::AnyAccel many = accel::make_accel("auto", nullptr, row_of_boxes(1000));
  EXPECT_EQ(accel::name_of(many), "bvh8");
  EXPECT_TRUE(std::holds_alternative<accel::Bvh8>(many));
  const json q = accel::params_of(many);
  EXPECT_EQ(q.at("max_leaf_size"), accel::Bvh8::Params{}.max_leaf_size);
  EXPECT_EQ(q.at("selected_by").at("structure"), "auto");
  EXPECT_GT(accel::stats_of(many).nodes, 1u);

  const accel::AnyAccel forced = accel::make_accel("auto", {{"naive_max_prims", 2000}}, row_of_boxes(1000));
  EXPECT_EQ(accel::name_of(forced), "naive");
}

TEST(AccelFactory, MemoryBudgetErrorNamesTheKnob) {
  const auto boxes = row_of_boxes(1000);
  try {
    accel::make_accel("bvh", nullptr, boxes, accel::BuildLimits{1024, {}});
    FAIL() << "expected ConfigError";
  } catch (const knobs::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--max-memory"), std::string::npos) << e.what();
  }
}

}  // namespace
