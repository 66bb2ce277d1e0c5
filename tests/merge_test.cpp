// `accelbench merge`: shards of a sweep join into exactly the whole sweep; a repeated
// configuration or another sweep's file is refused; a missing shard is reported; shards from
// different hardware are recorded and flagged.

#include "harness/sweep_definition.h"
#include "harness/sweep_machine.h"
#include "harness/sweep_results.h"
#include "harness/sweep_runner.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

harness::SweepDefinition tiny() {
  return harness::parse_sweep_definition(
      {{"name", "tiny-merge"},
       {"scenes", {"random:25", "grid:27"}},
       {"structures", {"naive", "octree", {{"name", "kdtree"}, {"split", {"midpoint", "sah"}}}, "bvh"}},
       {"knobs", {{"max_leaf_size", {1, 4}}}},
       {"resolution", "10x8"},
       {"repetitions", 1},
       {"warmup", 0}});
}

std::set<std::string> keys_of(const json& doc) {
  std::set<std::string> keys;
  for (const auto& r : doc["rows"]) keys.insert(r["key"].get<std::string>());
  return keys;
}

class MergeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("accelbench_merge_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  json run(const harness::SweepDefinition& d, int index, int count) {
    harness::RunOptions o;
    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
    std::string name = std::to_string(index);
    name += "of";
    name += std::to_string(count);
    name += ".json";
    o.out_path = (dir_ / name).string();
    o.jsonl_path = o.out_path + "l";
    o.shard_index = index;
    o.shard_count = count;
    o.progress = false;
    harness::run_sweep(d, o);
    return harness::read_results_file(o.out_path);
  }

  fs::path dir_;
};

TEST_F(MergeTest, ShardsMergeIntoExactlyTheFullSweep) {
  const auto d = tiny();
  const auto all = harness::expand(d);
  std::set<std::string> all_keys;
  for (const auto& c : all) all_keys.insert(c.key);

  std::vector<std::pair<std::string, json>> shards;
  std::size_t rows = 0;
  for (int i = 0; i < 3; ++i) {
    shards.emplace_back("shard" + std::to_string(i), run(d, i, 3));
    EXPECT_TRUE(shards.back().second["complete"].get<bool>());
    rows += shards.back().second["rows"].size();
  }
  EXPECT_EQ(rows, all.size());
  const json merged = harness::merge_results(shards);
  EXPECT_EQ(keys_of(merged), all_keys);
  EXPECT_EQ(merged["rows"].size(), all.size());
  EXPECT_TRUE(merged["complete"].get<bool>());
  EXPECT_TRUE(merged["missing"].empty());
  for (std::size_t i = 0; i < merged["rows"].size(); ++i) EXPECT_EQ(merged["rows"][i]["index"], i);
  // Every row is validated against naive, whichever shard measured naive itself.
  for (const auto& r : merged["rows"]) {
    EXPECT_EQ(r["status"], "ok") << r.dump();
    EXPECT_EQ(r["image_hash"], r["naive_image_hash"]);
  }

  // Merging the shards' merge with nothing else is the identity on rows.
  EXPECT_EQ(keys_of(harness::merge_results({{"merged", merged}})), all_keys);

  // A missing shard is reported, not hidden.
  const json partial = harness::merge_results({shards[0], shards[2]});
  EXPECT_FALSE(partial["complete"].get<bool>());
  EXPECT_EQ(partial["missing"].size(), shards[1].second["rows"].size());

  // The same configuration twice is refused, naming both files.
  try {
    harness::merge_results({shards[0], shards[1], {"again", shards[0].second}});
    ADD_FAILURE() << "duplicate accepted";
  } catch (const harness::SweepError& e) {
    EXPECT_NE(std::string(e.what()).find("is also in shard0"), std::string::npos) << e.what();
  }
}

TEST_F(MergeTest, RefusesShardsOfAnotherSweep) {
  auto other = tiny();
  other.repetitions = 2;
  const json a = run(tiny(), 0, 2), b = run(other, 1, 2);
  try {
    harness::merge_results({{"a.json", a}, {"b.json", b}});
    ADD_FAILURE() << "different definitions accepted";
  } catch (const harness::SweepError& e) {
    EXPECT_EQ(std::string(e.what()), "b.json: /sweep: differs from a.json's sweep definition");
  }
}

TEST_F(MergeTest, RecordsAndWarnsWhenShardsRanOnDifferentHardware) {
  const auto d = tiny();
  const json a = run(d, 0, 2), b = run(d, 1, 2);
  const json merged = harness::merge_results({{"a", a}, {"b", b}});
  EXPECT_FALSE(merged.contains("mixed_hardware"));
  EXPECT_FALSE(merged.contains("machines"));
  EXPECT_EQ(merged["speedup_basis"], harness::kSpeedupBasis);

  // Another node of the same hardware: both machines are recorded, nothing is mixed.
  json other_node = b;
  other_node["machine"]["hostname"] = "node-b";
  json m = harness::merge_results({{"a", a}, {"b", other_node}});
  ASSERT_TRUE(m.contains("machines"));
  EXPECT_EQ(m["machines"].size(), 2u);
  EXPECT_FALSE(m.contains("mixed_hardware"));

  // Another core count, then another CPU model: flagged, with both values.
  json other_cores = other_node;
  other_cores["machine"]["cores"] = a["machine"]["cores"].get<int>() + 62;
  m = harness::merge_results({{"a", a}, {"b", other_cores}});
  ASSERT_TRUE(m.contains("mixed_hardware"));
  EXPECT_EQ(m["mixed_hardware"]["cores"],
            json::array({a["machine"]["cores"], other_cores["machine"]["cores"]}));
  EXPECT_EQ(m["mixed_hardware"]["cpu_models"].size(), 1u);

  json other_cpu = other_node;
  other_cpu["machine"]["cpu_model"] = "Other CPU @ 1.0GHz";
  m = harness::merge_results({{"a", a}, {"b", other_cpu}});
  ASSERT_TRUE(m.contains("mixed_hardware"));
  EXPECT_EQ(m["mixed_hardware"]["cpu_models"],
            json::array({a["machine"]["cpu_model"], "Other CPU @ 1.0GHz"}));
  EXPECT_NE(m["mixed_hardware"]["warning"].get<std::string>().find("Other CPU @ 1.0GHz"),
            std::string::npos);
  // merged_from still tells which shard ran where.
  EXPECT_EQ(m["merged_from"][1]["machine"]["cpu_model"], "Other CPU @ 1.0GHz");

  // A shard that was itself resumed on other hardware carries both machines; merge sees them.
  json resumed = b;
  resumed["machines"] = json::array({b["machine"], other_cpu["machine"]});
  m = harness::merge_results({{"a", a}, {"b", resumed}});
  EXPECT_TRUE(m.contains("mixed_hardware"));

  // The command line says so on stderr and exits 0 (the merge itself is complete).
  std::ofstream(dir_ / "a.json") << a.dump();
  std::ofstream(dir_ / "b.json") << other_cpu.dump();
  const std::string cmd = std::string(ACCELBENCH_CLI) + " merge " + (dir_ / "a.json").string() +
                          " " + (dir_ / "b.json").string() + " -o " + (dir_ / "m.json").string() +
                          " 2> " + (dir_ / "err.txt").string();
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream err_in(dir_ / "err.txt");
  const std::string err((std::istreambuf_iterator<char>(err_in)), std::istreambuf_iterator<char>());
  EXPECT_NE(err.find("merge: warning: rows were measured on different hardware"), std::string::npos)
      << err;
  EXPECT_NE(err.find("Other CPU @ 1.0GHz"), std::string::npos) << err;
  EXPECT_TRUE(harness::read_results_file((dir_ / "m.json").string()).contains("mixed_hardware"));
}

}  // namespace
