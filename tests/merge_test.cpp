// `accelbench merge`: shards of a sweep join into exactly the whole sweep; a repeated
// configuration or another sweep's file is refused; a missing shard is reported.

#include "bench/sweep_definition.h"
#include "bench/sweep_results.h"
#include "bench/sweep_runner.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

bench::SweepDefinition tiny() {
  return bench::parse_sweep_definition(
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

  json run(const bench::SweepDefinition& d, int index, int count) {
    bench::RunOptions o;
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
    bench::run_sweep(d, o);
    return bench::read_results_file(o.out_path);
  }

  fs::path dir_;
};

TEST_F(MergeTest, ShardsMergeIntoExactlyTheFullSweep) {
  const auto d = tiny();
  const auto all = bench::expand(d);
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
  const json merged = bench::merge_results(shards);
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
  EXPECT_EQ(keys_of(bench::merge_results({{"merged", merged}})), all_keys);

  // A missing shard is reported, not hidden.
  const json partial = bench::merge_results({shards[0], shards[2]});
  EXPECT_FALSE(partial["complete"].get<bool>());
  EXPECT_EQ(partial["missing"].size(), shards[1].second["rows"].size());

  // The same configuration twice is refused, naming both files.
  try {
    bench::merge_results({shards[0], shards[1], {"again", shards[0].second}});
    ADD_FAILURE() << "duplicate accepted";
  } catch (const bench::SweepError& e) {
    EXPECT_NE(std::string(e.what()).find("is also in shard0"), std::string::npos) << e.what();
  }
}

TEST_F(MergeTest, RefusesShardsOfAnotherSweep) {
  auto other = tiny();
  other.repetitions = 2;
  const json a = run(tiny(), 0, 2), b = run(other, 1, 2);
  try {
    bench::merge_results({{"a.json", a}, {"b.json", b}});
    ADD_FAILURE() << "different definitions accepted";
  } catch (const bench::SweepError& e) {
    EXPECT_EQ(std::string(e.what()), "b.json: /sweep: differs from a.json's sweep definition");
  }
}

}  // namespace
