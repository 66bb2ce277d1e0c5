// Timing statistics of a sweep row (harness/sweep_stats.h) and the JSON Lines file rows are
// appended to (harness/sweep_jsonl.h): complete lines kept, a torn last line dropped.

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

#include "sweep_cli.h"

namespace {

using harness::SweepError;
using nlohmann::json;
namespace fs = std::filesystem;

using sweep_cli::temp_dir;

TEST(SweepStats, MedianQuartilesAndSpread) {
  const auto s = harness::summarize({5.0, 1.0, 4.0, 2.0, 3.0});
  EXPECT_DOUBLE_EQ(s.median, 3.0);
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 5.0);
  EXPECT_DOUBLE_EQ(s.q1, 2.0);
  EXPECT_DOUBLE_EQ(s.q3, 4.0);
  EXPECT_DOUBLE_EQ(s.iqr(), 2.0);
  EXPECT_EQ(s.samples, (std::vector<double>{5.0, 1.0, 4.0, 2.0, 3.0}));  // measurement order kept
  const auto even = harness::summarize({4.0, 1.0, 3.0, 2.0});
  EXPECT_DOUBLE_EQ(even.median, 2.5);
  EXPECT_DOUBLE_EQ(even.q1, 1.75);
  const auto one = harness::summarize({7.0});
  EXPECT_DOUBLE_EQ(one.median, 7.0);
  EXPECT_DOUBLE_EQ(one.iqr(), 0.0);
}

TEST(SweepJsonl, KeepsCompleteLinesAndDropsATornOne) {
  const fs::path dir = temp_dir("jsonl");
  const std::string path = (dir / "rows.jsonl").string();
  {
    harness::JsonlWriter w(path, true);
    w.append({{"kind", "row"}, {"key", "a"}});
    w.append({{"kind", "row"}, {"key", "b"}});
  }
  const auto whole = fs::file_size(path);
  {
    std::ofstream out(path, std::ios::app);
    out << "{\"kind\":\"row\",\"key\":\"c";  // a write cut by a kill
  }
  const auto c = harness::read_jsonl(path);
  ASSERT_EQ(c.records.size(), 2u);
  EXPECT_EQ(c.records[1]["key"], "b");
  EXPECT_TRUE(c.torn_tail);
  EXPECT_EQ(c.lines, (std::vector<std::size_t>{1, 2}));
  EXPECT_EQ(c.valid_bytes, whole);
  harness::truncate_file(path, c.valid_bytes);
  {
    harness::JsonlWriter w(path, false);
    w.append({{"kind", "row"}, {"key", "c"}});
  }
  const auto after = harness::read_jsonl(path);
  EXPECT_EQ(after.records.size(), 3u);
  EXPECT_FALSE(after.torn_tail);
  EXPECT_TRUE(harness::read_jsonl((dir / "absent.jsonl").string()).records.empty());
  // A damaged line that is not the last is corruption, not a kill: refused with its line number.
  try {
    harness::parse_jsonl("{\"kind\":\"row\"}\n{\"kind\":\"ro\n{\"kind\":\"row\"}\n", "x.jsonl");
    ADD_FAILURE() << "a damaged middle line was accepted";
  } catch (const SweepError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("x.jsonl:2: /kind: invalid JSON: ", 0), 0u) << e.what();
  }
  EXPECT_THROW(harness::parse_jsonl("[1]\n", "x.jsonl"), SweepError);  // not an object
  fs::remove_all(dir);
}

}  // namespace
