// Sweep definitions: parsing with errors that name the JSON pointer, the normal form, expansion
// of knobs and integrator knob groups, canonical keys, and shards.

#include "harness/bootstrap.h"
#include "harness/sweep_definition.h"
#include "harness/sweep_jsonl.h"
#include "harness/sweep_machine.h"
#include "harness/sweep_runner.h"
#include "harness/sweep_stats.h"

#include "cli_run.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

using harness::SweepError;
using nlohmann::json;
namespace fs = std::filesystem;

std::string parse_error(const json& j) {
  try {
    harness::parse_sweep_definition(j);
  } catch (const SweepError& e) {
    return e.what();
  }
  return "(no error)";
}

json minimal() { return {{"scenes", {"five"}}, {"structures", {"naive"}}}; }

TEST(SweepDefinition, ErrorsNameTheJsonPointer) {
  struct Case {
    json patch;  // merged into the minimal definition
    std::string message;
  };
  const std::vector<Case> cases = {
      {{{"repetitions", 0}}, "/repetitions: must be in [1, 10000], got 0"},
      {{{"warmup", "1"}}, "/warmup: must be an integer, got \"1\""},
      {{{"scenes", json::array()}}, "/scenes: must be a non-empty array"},
      {{{"scenes", {"five", 3}}}, "/scenes/1: a scene must be a string or an object, got 3"},
      {{{"scenes", {{{"generator", "random"}, {"count", -5}}}}}, "/scenes/0/count: must be in [0, 10000000], got -5"},
      {{{"scenes", {{{"generator", "random"}, {"file", "x.nff"}}}}},
       "/scenes/0: a scene needs exactly one of 'generator' or 'file'"},
      {{{"scenes", {"five", "five"}}}, "/scenes/1: scene name 'five' is used twice; give one a 'name'"},
      {{{"structures", {"naive", "kdtre"}}}, "/structures/1/name: unknown structure 'kdtre'"},
      {{{"structures", {{{"name", "kdtree"}, {"max_depth", json::array()}}}}},
       "/structures/0/max_depth: must list at least one value"},
      {{{"structures", {{{"name", "kdtree"}, {"leafsize", 4}}}}}, "/structures/0/leafsize: kdtree: unknown knob 'leafsize' (its knobs: "},
      {{{"structures", {{{"name", "octree"}, {"max_depth", {4, {{"x", 1}}}}}}}},
       "/structures/0/max_depth/1: knob value must be a number, string or boolean"},
      {{{"knobs", {{"leafsize", {1, 2}}}}}, "/knobs/leafsize: no structure in this sweep has the knob 'leafsize'"},
      {{{"resolution", "64by48"}}, "/resolution: expected WIDTHxHEIGHT"},
      {{{"colour", 1}}, "/colour: unknown key"},
      {{{"integrator", "phong"}}, "/integrator: unknown integrator \"phong\" (known: whitted, spd"},
      {{{"mode", "phong"}}, "/mode: unknown integrator \"phong\" (known: whitted, spd"},
      {{{"mode", "spd"}, {"integrator", "spd"}}, "/mode: give \"integrator\" or its older name \"mode\", not both"},
      {{{"validate_resolution", "64"}}, "/validate_resolution: expected WIDTHxHEIGHT"},
      {{{"scenes", {{{"generator", "random"}, {"model", "bunny"}}}}},
       "/scenes/0/model: generator 'random' takes no model (only mesh and mesh_grid do)"},
      {{{"scenes", {{{"file", "a.json"}, {"model", "bunny"}}}}}, "/scenes/0/model: only generator scenes take this key"},
      {{{"scenes", {{{"generator", "mesh"}, {"model", ""}}}}}, "/scenes/0/model: must not be empty"},
  };
  for (const auto& c : cases) {
    json j = minimal();
    j.merge_patch(c.patch);
    const std::string got = parse_error(j);
    EXPECT_EQ(got.rfind(c.message, 0), 0u) << "patch " << c.patch.dump() << "\n got: " << got;
    EXPECT_EQ(got.find('\n'), std::string::npos);
  }
}

TEST(SweepDefinition, RoundTripsThroughItsNormalForm) {
  const json j = {{"name", "t"},
                  {"scenes", {"five", "random:50", {{"file", "a/b/teapot.nff"}},
                              {{"generator", "mesh_grid"}, {"model", "../meshes/ogre.obj"}, {"count", 5000}}}},
                  {"structures", {"naive", {{"name", "kdtree"}, {"split", "sah"}, {"max_leaf_size", {1, 2}}}}},
                  {"knobs", {{"max_depth", {4, 8}}}},
                  {"resolution", "32x24"}};
  const auto d = harness::parse_sweep_definition(j);
  EXPECT_EQ(d.scenes[1].name, "random-50");
  EXPECT_EQ(d.scenes[1].count, 50);
  EXPECT_FALSE(d.scenes[0].count.has_value());
  EXPECT_EQ(d.scenes[2].name, "teapot");
  EXPECT_EQ(d.scenes[3].name, "mesh_grid-ogre-5000") << "a model names its scene";
  EXPECT_EQ(d.scenes[3].model, "../meshes/ogre.obj");
  EXPECT_EQ(d.width, 32);
  const json normal = harness::to_json(d);
  EXPECT_EQ(harness::to_json(harness::parse_sweep_definition(normal)), normal);
}

TEST(SweepDefinition, ExpandsKnobsOnlyForStructuresThatHaveThem) {
  const json j = {{"scenes", {"five", "random:20"}},
                  {"structures", {"naive", "octree", {{"name", "kdtree"}, {"max_depth", {3}}}}},
                  {"knobs", {{"max_depth", {4, 8, 12}}, {"max_leaf_size", {1, 2}}}}};
  const auto configs = harness::expand(harness::parse_sweep_definition(j));
  std::map<std::string, int> per_structure;
  std::set<std::string> keys;
  for (std::size_t i = 0; i < configs.size(); ++i) {
    EXPECT_EQ(configs[i].index, i);
    per_structure[configs[i].structure]++;
    keys.insert(configs[i].key);
    if (configs[i].structure == "naive") {
      EXPECT_TRUE(configs[i].params.empty());
    }
    if (configs[i].structure == "kdtree") {
      EXPECT_EQ(configs[i].params["max_depth"], 3);
    }
  }
  EXPECT_EQ(keys.size(), configs.size());
  EXPECT_EQ(per_structure["naive"], 2);        // once per scene
  EXPECT_EQ(per_structure["octree"], 2 * 6);   // 3 depths x 2 leaf sizes per scene
  EXPECT_EQ(per_structure["kdtree"], 2 * 2);   // its own depth x 2 leaf sizes
  // Scene-major order: all of the first scene's configurations come first.
  EXPECT_EQ(configs.front().scene, 0u);
  EXPECT_EQ(configs.back().scene, 1u);
  EXPECT_TRUE(std::is_sorted(configs.begin(), configs.end(),
                             [](const auto& a, const auto& b) { return a.scene < b.scene; }));
}

TEST(SweepDefinition, KeyIsCanonical) {
  EXPECT_EQ(harness::config_key("s", "kdtree", json{{"max_leaf_size", 2}, {"max_depth", 8}}),
            harness::config_key("s", "kdtree", json{{"max_depth", 8}, {"max_leaf_size", 2}}));
  EXPECT_NE(harness::config_key("s", "kdtree", json{{"max_depth", 8}}),
            harness::config_key("s", "octree", json{{"max_depth", 8}}));
}

TEST(SweepDefinition, IntegratorKnobGroupsAreCrossedWithinAndJoinedAcross) {
  // One group: its knobs crossed. Several: joined (one knob at a time), repeats dropped.
  json j = {{"scenes", {"five"}},
            {"structures", {"naive", {{"name", "kdtree"}, {"max_leaf_size", {1, 2}}}}},
            {"integrator_knobs", {{"max_depth", {1, 2, 3}}, {"spp", {1, 4}}}}};
  auto d = harness::parse_sweep_definition(j);
  ASSERT_EQ(d.integrator_knobs.size(), 1u);
  EXPECT_EQ(harness::expand(d).size(), (1u + 2u) * 6u);
  j["integrator_knobs"] = json::array({{{"max_depth", {1, 2, 3}}}, {{"spp", {1, 4}}}, {{"spp", {4}}}});
  d = harness::parse_sweep_definition(j);
  const auto configs = harness::expand(d);
  EXPECT_EQ(configs.size(), (1u + 2u) * 5u);
  std::set<std::string> keys;
  for (const auto& c : configs) {
    keys.insert(c.key);
    EXPECT_EQ(c.integrator_params.size(), 1u);
    EXPECT_EQ(c.key, harness::config_key("five", c.structure, c.params, c.integrator_params));
  }
  EXPECT_EQ(keys.size(), configs.size());
  const json normal = harness::to_json(d);
  EXPECT_EQ(harness::to_json(harness::parse_sweep_definition(normal)), normal);
  // Without integrator knobs the keys are what they always were.
  EXPECT_EQ(harness::config_key("s", "bvh", json::object(), json::object()), "s|bvh|{}");
  EXPECT_EQ(harness::config_key("s", "bvh", json::object(), {{"spp", 4}}), "s|bvh|{}|{\"spp\":4}");

  for (const auto& [patch, message] : std::vector<std::pair<json, std::string>>{
           {{{"integrator_knobs", {{"depth", {1}}}}}, "/integrator_knobs/depth: integrator whitted has no knob 'depth'"},
           {{{"integrator_knobs", {{"max_depth", {1, 5000}}}}}, "/integrator_knobs/max_depth/1: whitted: knob 'max_depth'"},
           {{{"integrator_knobs", json::array()}}, "/integrator_knobs: must list at least one group"},
           {{{"integrator_knobs", json::array({json::object()})}}, "/integrator_knobs/0: must name at least one"},
           {{{"integrator", "spd"}, {"integrator_knobs", {{"spp", {1}}}}}, "/integrator_knobs/spp: integrator spd has no knob"},
       }) {
    json bad = minimal();
    bad.merge_patch(patch);
    const std::string got = parse_error(bad);
    EXPECT_EQ(got.rfind(message, 0), 0u) << got;
  }
}

TEST(SweepDefinition, ShardsAreDisjointAndCoverTheSweep) {
  const json j = {{"scenes", {"five", "random:20", "grid:8"}},
                  {"structures", {"naive", "octree", "kdtree"}},
                  {"knobs", {{"max_depth", {2, 4, 6}}, {"max_leaf_size", {1, 3}}}}};
  const auto all = harness::expand(harness::parse_sweep_definition(j));
  for (int n : {1, 2, 3, 7, int(all.size()) + 2}) {
    std::multiset<std::string> seen;
    for (int i = 0; i < n; ++i) {
      const auto part = harness::shard(all, i, n);
      EXPECT_EQ(harness::shard(all, i, n).size(), part.size());  // deterministic
      for (const auto& c : part) seen.insert(c.key);
    }
    EXPECT_EQ(seen.size(), all.size()) << n << " shards";
    for (const auto& c : all) EXPECT_EQ(seen.count(c.key), 1u);
  }
  EXPECT_THROW(harness::parse_shard("3/3"), SweepError);
  EXPECT_THROW(harness::parse_shard("1"), SweepError);
  EXPECT_EQ(harness::parse_shard("2/5"), std::make_pair(2, 5));
}

}  // namespace
