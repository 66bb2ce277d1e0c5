// Resuming a sweep: after a real SIGKILL and a SIGTERM of the `accelbench sweep` process, after
// a corrupted row, and on another node (naive measured again, both machines recorded).

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

using sweep_cli::outcome;
using sweep_cli::read_json;
using sweep_cli::run_cli;
using sweep_cli::signal_after;
using sweep_cli::temp_dir;
using sweep_cli::tiny_sweep_args;
using sweep_cli::valid_against_schema;
using sweep_cli::write_tiny_definition;

TEST(SweepResume, AKilledRunResumesToTheSameRowsAsAnUninterruptedOne) {
  const fs::path dir = temp_dir("resume");
  write_tiny_definition(dir);

  int st = run_cli(tiny_sweep_args(dir, "whole"));
  ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << st;
  const json whole = read_json(dir / "whole.json");
  EXPECT_TRUE(whole["complete"].get<bool>());
  const auto expected = outcome(whole);
  ASSERT_EQ(expected.size(), 2u * (1 + 4 + 1 + 1));
  // Leaf size 0 is an invalid knob: a failed row, and the sweep went on.
  EXPECT_EQ(expected.at(harness::config_key("grid-8", "octree", {{"max_depth", 1}, {"max_leaf_size", 0}})).first,
            "failed");

  // A real SIGKILL after three rows: no clean-up code runs.
  st = run_cli(tiny_sweep_args(dir, "killed"), signal_after(3, SIGKILL));
  ASSERT_TRUE(WIFSIGNALED(st) && WTERMSIG(st) == SIGKILL) << st;
  EXPECT_FALSE(fs::exists(dir / "killed.json"));
  const auto partial = harness::read_jsonl((dir / "killed.jsonl").string());
  ASSERT_EQ(partial.records.size(), 1u + 3u);  // header + three rows
  EXPECT_FALSE(partial.torn_tail);

  // SIGTERM after two more rows: a clean stop that writes the results so far. The rows of the
  // batch being written are all measured (their rounds are done), so they go out too; the next
  // scene is not started.
  auto args = tiny_sweep_args(dir, "killed");
  args.push_back("--resume");
  st = run_cli(args, signal_after(2, SIGTERM));
  ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 130) << st;
  const json stopped = read_json(dir / "killed.json");
  EXPECT_FALSE(stopped["complete"].get<bool>());
  EXPECT_GE(stopped["rows"].size(), 5u);
  EXPECT_LT(stopped["rows"].size(), expected.size());
  EXPECT_EQ(stopped["rows"].size() + stopped["missing"].size(), expected.size());

  st = run_cli(args);
  ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << st;
  const json resumed = read_json(dir / "killed.json");
  EXPECT_TRUE(resumed["complete"].get<bool>());
  EXPECT_EQ(outcome(resumed), expected);
  EXPECT_EQ(resumed["runs"].size(), 2u);  // the killed run wrote no run record

  // --resume refuses a file written by another sweep definition.
  std::ofstream(dir / "tiny.json") << json{{"name", "tiny"}, {"scenes", {"five"}}, {"structures", {"naive"}}}.dump();
  st = run_cli(args);
  EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) != 0) << st;
  fs::remove_all(dir);
}

std::vector<std::string> lines_of(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

void write_lines(const fs::path& p, const std::vector<std::string>& lines) {
  std::ofstream out(p, std::ios::trunc);
  for (const auto& l : lines) out << l << '\n';
}

// A corrupted first row (its key, or no key) once made --resume keep the bogus row,
// drop the real naive row and still write "complete": true. Now the resume stops at that line
// and leaves the file alone; once the line is mended or removed, the resume measures exactly
// what is missing, and every real configuration is in the results.
TEST(SweepResume, ACorruptedRowStopsTheResumeAndEveryRealConfigurationIsKept) {
  const fs::path dir = temp_dir("corrupt");
  write_tiny_definition(dir);
  int st = run_cli(tiny_sweep_args(dir, "whole"));
  ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << st;
  const auto expected = outcome(read_json(dir / "whole.json"));
  const std::vector<std::string> lines = lines_of(dir / "whole.jsonl");
  ASSERT_GE(lines.size(), 4u);

  // Naive's row and two others: what a run killed after three rows may hold.
  const std::string naive_key = harness::config_key("random-30", "naive", json::object());
  std::size_t naive_line = 0;
  for (std::size_t i = 1; i < lines.size(); ++i)
    if (json::parse(lines[i]).value("key", "") == naive_key) naive_line = i;
  ASSERT_GT(naive_line, 0u);
  std::vector<std::string> others;
  for (std::size_t i = 1; i < lines.size() && others.size() < 2; ++i)
    if (i != naive_line && json::parse(lines[i]).value("kind", "") == "row") others.push_back(lines[i]);
  ASSERT_EQ(others.size(), 2u);

  for (const std::string damage : {"key", "no key"}) {
    json first = json::parse(lines[naive_line]);
    if (damage == "key")
      first["key"] = "random-30|naive|{\"bogus\":1}";
    else
      first.erase("key");
    std::vector<std::string> damaged = {lines[0], first.dump(), others[0], others[1]};
    write_lines(dir / "cut.jsonl", damaged);
    const auto before = lines_of(dir / "cut.jsonl");
    auto args = tiny_sweep_args(dir, "cut");
    args.push_back("--resume");
    st = run_cli(args);
    EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 1) << damage << ": " << st;
    EXPECT_EQ(lines_of(dir / "cut.jsonl"), before) << damage << ": the file was changed";
    EXPECT_FALSE(fs::exists(dir / "cut.json")) << damage << ": results were written";

    // The user removes the bad line: the resume measures the rest, naive included.
    write_lines(dir / "cut.jsonl", {lines[0], others[0], others[1]});
    st = run_cli(args);
    ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << damage << ": " << st;
    const json resumed = read_json(dir / "cut.json");
    EXPECT_TRUE(resumed["complete"].get<bool>()) << damage;
    EXPECT_TRUE(resumed["missing"].empty()) << damage;
    EXPECT_EQ(outcome(resumed), expected) << damage;
    fs::remove(dir / "cut.json");
  }
  fs::remove_all(dir);
}

/// Rewrites every record of a JSON Lines file through `edit`.
template <class Edit>
void edit_jsonl(const fs::path& path, Edit edit) {
  auto contents = harness::read_jsonl(path.string());
  std::ofstream out(path, std::ios::trunc);
  for (auto& r : contents.records) {
    edit(r);
    out << r.dump() << "\n";
  }
}

/// The first `rows` rows of the tiny sweep, killed after them, as if measured on `node` with a
/// CPU and core count of its own, and naive's median render time replaced by an impossible 1e9 ms
/// (a reused naive row then shows in every later row's naive_render_ms).
void killed_on(const fs::path& dir, const std::string& name, std::size_t rows,
               const std::string& node) {
  const int st = run_cli(tiny_sweep_args(dir, name), signal_after(rows, SIGKILL));
  ASSERT_TRUE(WIFSIGNALED(st) && WTERMSIG(st) == SIGKILL) << st;
  edit_jsonl(dir / (name + ".jsonl"), [&](json& r) {
    if (r["kind"] == "header" && !node.empty())
      r["machine"].update(
          {{"hostname", node}, {"cpu_model", "Other CPU @ 1.0GHz"}, {"cores", 1234}});
    if (r["kind"] != "row") return;
    if (!node.empty()) r["node"] = node;
    if (r["structure"] == "naive") r["render_ms"]["median"] = 1e9;
  });
}

TEST(SweepResume, OnAnotherNodeMeasuresNaiveAgainAndRecordsBothMachines) {
  const fs::path dir = temp_dir("resume_node");
  write_tiny_definition(dir);
  const std::string here = harness::node_name(harness::machine_info());
  ASSERT_FALSE(here.empty());
  ASSERT_NE(here, "node-a");
  const std::string first_scene_naive = harness::config_key("random-30", "naive", json::object());

  // Resumed on the node that measured naive: naive is timed again anyway, in the same
  // interleaved rounds as the rows it is the reference for (the 1e9 does not show through).
  killed_on(dir, "same", 3, "");
  auto args = tiny_sweep_args(dir, "same");
  args.push_back("--resume");
  int st = run_cli(args);
  ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << st;
  const json same = read_json(dir / "same.json");
  std::size_t timed_again = 0;
  for (const auto& r : same["rows"])
    if (r["scene"] == "random-30" && r["structure"] != "naive" && r.contains("naive_render_ms")) {
      EXPECT_LT(r["naive_render_ms"].get<double>(), 1e6) << r["key"];
      if (r["node"] == here) ++timed_again;
    }
  EXPECT_GE(timed_again, 3u);
  EXPECT_FALSE(same.contains("machines"));
  EXPECT_FALSE(same.contains("mixed_hardware"));

  // Resumed on another node with another CPU: naive is measured again here, and the results
  // file names both machines and flags the mixed hardware.
  killed_on(dir, "moved", 3, "node-a");
  args = tiny_sweep_args(dir, "moved");
  args.push_back("--resume");
  st = run_cli(args);
  ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << st;
  const json moved = read_json(dir / "moved.json");
  EXPECT_TRUE(moved["complete"].get<bool>());
  ASSERT_EQ(moved["rows"].size(), same["rows"].size());
  std::size_t remeasured = 0, from_a = 0;
  for (const auto& r : moved["rows"]) {
    if (r["node"] == "node-a") {
      ++from_a;
      continue;
    }
    EXPECT_EQ(r["node"], here);
    if (r["scene"] == "random-30" && r.contains("naive_render_ms")) {
      EXPECT_LT(r["naive_render_ms"].get<double>(), 1e6) << r["key"];
      ++remeasured;
    }
  }
  EXPECT_EQ(from_a, 3u);
  EXPECT_GE(remeasured, 3u);
  ASSERT_TRUE(moved.contains("machines"));
  EXPECT_EQ(moved["machines"].size(), 2u);
  ASSERT_TRUE(moved.contains("mixed_hardware"));
  EXPECT_EQ(moved["mixed_hardware"]["cpu_models"][0], "Other CPU @ 1.0GHz");
  EXPECT_EQ(moved["mixed_hardware"]["cores"][0], 1234);
  EXPECT_EQ(moved["speedup_basis"], harness::kSpeedupBasis);
  EXPECT_EQ(outcome(moved), outcome(same));
  EXPECT_TRUE(valid_against_schema(moved, dir));
  fs::remove_all(dir);
}

}  // namespace
