// The sweep harness: definition parsing and expansion, timing statistics, sharding, the JSON
// Lines file, and resuming after a real kill of the `accelbench sweep` process.

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
                  {"scenes", {"five", "random:50", {{"file", "a/b/teapot.nff"}}}},
                  {"structures", {"naive", {{"name", "kdtree"}, {"split", "sah"}, {"max_leaf_size", {1, 2}}}}},
                  {"knobs", {{"max_depth", {4, 8}}}},
                  {"resolution", "32x24"}};
  const auto d = harness::parse_sweep_definition(j);
  EXPECT_EQ(d.scenes[1].name, "random-50");
  EXPECT_EQ(d.scenes[1].count, 50);
  EXPECT_FALSE(d.scenes[0].count.has_value());
  EXPECT_EQ(d.scenes[2].name, "teapot");
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

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("accelbench_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
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

/// Runs the CLI with extra environment; returns the raw wait status.
int run_cli(const std::vector<std::string>& args, const std::vector<std::string>& env_extra) {
  const pid_t pid = fork();
  if (pid == 0) {
    for (const auto& e : env_extra) putenv(const_cast<char*>(e.c_str()));
    if (!freopen("/dev/null", "w", stderr)) _exit(126);
    std::vector<char*> argv;
    std::string exe = ACCELBENCH_CLI;
    argv.push_back(exe.data());
    std::vector<std::string> copy = args;
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(exe.c_str(), argv.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

json read_json(const fs::path& p) {
  std::ifstream in(p);
  return json::parse(in);
}

/// key -> (status, image hash): what a sweep found, without its timings.
std::map<std::string, std::pair<std::string, std::string>> outcome(const json& results) {
  std::map<std::string, std::pair<std::string, std::string>> out;
  for (const auto& r : results["rows"]) out[r["key"]] = {r["status"], r.value("image_hash", "")};
  return out;
}

std::vector<std::string> tiny_sweep_args(const fs::path& dir, const std::string& name) {
  return {"sweep",   "--config", (dir / "tiny.json").string(), "--out", (dir / (name + ".json")).string(),
          "--quiet"};
}

void write_tiny_definition(const fs::path& dir) {
  std::ofstream(dir / "tiny.json") << json{
      {"name", "tiny"},
      {"scenes", {"random:30", "grid:8"}},
      {"structures", {"naive", {{"name", "octree"}, {"max_depth", {1, 3}}, {"max_leaf_size", {0, 2}}}, "kdtree", "bvh"}},
      {"resolution", "12x9"},
      {"repetitions", 1},
      {"warmup", 0}}.dump();
}

TEST(SweepList, PrintsTheShardsKeysWithoutMeasuring) {
  const fs::path dir = temp_dir("list");
  write_tiny_definition(dir);
  const auto all = harness::expand(harness::load_sweep_file((dir / "tiny.json").string()));
  std::multiset<std::string> seen;
  for (int i = 0; i < 3; ++i) {
    const std::string cmd =
        std::string(ACCELBENCH_CLI) + " sweep --config " + (dir / "tiny.json").string() +
        " --out " + (dir / "never.json").string() + " --shard " + std::to_string(i) + "/3 --list";
    const cli_run::CliRun list = cli_run::run(cmd, /*join_stderr=*/false);
    ASSERT_EQ(list.status, 0);
    std::vector<std::string> keys;
    std::istringstream lines(list.output);
    for (std::string key; std::getline(lines, key);) keys.push_back(key);
    std::vector<std::string> expected;
    for (const auto& c : harness::shard(all, i, 3)) expected.push_back(c.key);
    EXPECT_EQ(keys, expected) << "shard " << i;
    seen.insert(keys.begin(), keys.end());
  }
  EXPECT_EQ(seen.size(), all.size());
  EXPECT_FALSE(fs::exists(dir / "never.json"));  // nothing measured, nothing written
  EXPECT_FALSE(fs::exists(dir / "never.jsonl"));
  fs::remove_all(dir);
}

TEST(SweepResume, AKilledRunResumesToTheSameRowsAsAnUninterruptedOne) {
  const fs::path dir = temp_dir("resume");
  write_tiny_definition(dir);

  int st = run_cli(tiny_sweep_args(dir, "whole"), {});
  ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << st;
  const json whole = read_json(dir / "whole.json");
  EXPECT_TRUE(whole["complete"].get<bool>());
  const auto expected = outcome(whole);
  ASSERT_EQ(expected.size(), 2u * (1 + 4 + 1 + 1));
  // Leaf size 0 is an invalid knob: a failed row, and the sweep went on.
  EXPECT_EQ(expected.at(harness::config_key("grid-8", "octree", {{"max_depth", 1}, {"max_leaf_size", 0}})).first,
            "failed");

  // A real SIGKILL after three rows: no clean-up code runs.
  st = run_cli(tiny_sweep_args(dir, "killed"), {"ACCELBENCH_SWEEP_KILL_AFTER_ROWS=3"});
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
  st = run_cli(args, {"ACCELBENCH_SWEEP_KILL_AFTER_ROWS=2", "ACCELBENCH_SWEEP_KILL_SIGNAL=TERM"});
  ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 130) << st;
  const json stopped = read_json(dir / "killed.json");
  EXPECT_FALSE(stopped["complete"].get<bool>());
  EXPECT_GE(stopped["rows"].size(), 5u);
  EXPECT_LT(stopped["rows"].size(), expected.size());
  EXPECT_EQ(stopped["rows"].size() + stopped["missing"].size(), expected.size());

  st = run_cli(args, {});
  ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << st;
  const json resumed = read_json(dir / "killed.json");
  EXPECT_TRUE(resumed["complete"].get<bool>());
  EXPECT_EQ(outcome(resumed), expected);
  EXPECT_EQ(resumed["runs"].size(), 2u);  // the killed run wrote no run record

  // --resume refuses a file written by another sweep definition.
  std::ofstream(dir / "tiny.json") << json{{"name", "tiny"}, {"scenes", {"five"}}, {"structures", {"naive"}}}.dump();
  st = run_cli(args, {});
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

// Issue 12: a corrupted first row (its key, or no key) once made --resume keep the bogus row,
// drop the real naive row and still write "complete": true. Now the resume stops at that line
// and leaves the file alone; once the line is mended or removed, the resume measures exactly
// what is missing, and every real configuration is in the results.
TEST(SweepResume, ACorruptedRowStopsTheResumeAndEveryRealConfigurationIsKept) {
  const fs::path dir = temp_dir("corrupt");
  write_tiny_definition(dir);
  int st = run_cli(tiny_sweep_args(dir, "whole"), {});
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
    st = run_cli(args, {});
    EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 1) << damage << ": " << st;
    EXPECT_EQ(lines_of(dir / "cut.jsonl"), before) << damage << ": the file was changed";
    EXPECT_FALSE(fs::exists(dir / "cut.json")) << damage << ": results were written";

    // The user removes the bad line: the resume measures the rest, naive included.
    write_lines(dir / "cut.jsonl", {lines[0], others[0], others[1]});
    st = run_cli(args, {});
    ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << damage << ": " << st;
    const json resumed = read_json(dir / "cut.json");
    EXPECT_TRUE(resumed["complete"].get<bool>()) << damage;
    EXPECT_TRUE(resumed["missing"].empty()) << damage;
    EXPECT_EQ(outcome(resumed), expected) << damage;
    fs::remove(dir / "cut.json");
  }
  fs::remove_all(dir);
}

/// True when `doc` validates against results/schema/results.schema.json (Python's jsonschema).
bool valid_against_schema(const json& doc, const fs::path& dir) {
  std::ofstream(dir / "validate.py") << "import json, sys\nimport jsonschema\n"
                                        "schema = json.load(open(sys.argv[1]))\n"
                                        "doc = json.load(open(sys.argv[2]))\n"
                                        "errors = list(jsonschema.Draft202012Validator(schema).iter_errors(doc))\n"
                                        "for e in errors[:5]: print(list(e.absolute_path), e.message[:200])\n"
                                        "sys.exit(1 if errors else 0)\n";
  std::ofstream(dir / "doc.json") << doc.dump();
  const std::string cmd = std::string(ACCELBENCH_PYTHON) + " " + (dir / "validate.py").string() + " " +
                          ACCELBENCH_SOURCE_DIR "/results/schema/results.schema.json " + (dir / "doc.json").string();
  return std::system(cmd.c_str()) == 0;
}

// Issue 12: every configuration of a scene, naive included, is timed once per round; speedups
// are naive's median over the row's within those rounds, with a bootstrap interval; CPU time
// is recorded beside wall time; a noisy row gets more rounds.
TEST(SweepTiming, RowsAreTimedInInterleavedRoundsWithNaive) {
  const fs::path dir = temp_dir("timing");
  for (const double threshold : {0.10, 0.0}) {
    json j = {{"name", "timing"},
              {"scenes", {"random:200", "five"}},
              {"structures", {"naive", {{"name", "kdtree"}, {"max_depth", {4, 12}}}, "bvh"}},
              {"resolution", "16x12"},
              {"repetitions", 3},
              {"warmup", 0}};
    if (threshold == 0.0) j["noise_threshold"] = 0.0, j["remeasure"] = 1;  // every row noisy: one more pass
    const auto d = harness::parse_sweep_definition(j);
    harness::RunOptions o;
    o.out_path = (dir / "t.json").string();
    o.jsonl_path = (dir / "t.jsonl").string();
    o.progress = false;
    const auto summary = harness::run_sweep(d, o);
    ASSERT_TRUE(summary.complete);
    const json doc = read_json(dir / "t.json");
    ASSERT_EQ(doc["rows"].size(), 8u);
    for (const auto& r : doc["rows"]) {
      ASSERT_EQ(r["status"], "ok") << r.dump();
      const json& t = r["render_ms"];
      const std::size_t rounds = 3 * (1 + r["remeasured"].get<std::size_t>());
      EXPECT_EQ(t["samples"].size(), rounds) << r["key"];
      EXPECT_EQ(r["cpu_ms"]["samples"].size(), rounds) << r["key"];
      EXPECT_GT(r["cpu_ms"]["median"].get<double>(), 0.0);
      EXPECT_LE(r["cpu_ms"]["min"].get<double>(), 1.5 * r["render_ms"]["max"].get<double>() + 1.0);  // one thread
      EXPECT_LE(r["render_ms_ci"][0].get<double>(), t["median"].get<double>());
      EXPECT_GE(r["render_ms_ci"][1].get<double>(), t["median"].get<double>());
      // The paired ratio: naive's time over the row's in each round the row was timed in (a
      // prefix of naive's rounds: a re-measure pass takes naive and the rows still noisy).
      const json& naive_row = *std::find_if(doc["rows"].begin(), doc["rows"].end(), [&](const json& x) {
        return x["scene"] == r["scene"] && x["structure"] == "naive";
      });
      std::vector<double> naive_ms, own_ms;
      for (std::size_t k = 0; k < rounds; ++k) {
        naive_ms.push_back(naive_row["render_ms"]["samples"][k].get<double>());
        own_ms.push_back(t["samples"][k].get<double>());
      }
      EXPECT_DOUBLE_EQ(r["speedup"].get<double>(), harness::paired_ratio(naive_ms, own_ms)) << r["key"];
      EXPECT_DOUBLE_EQ(r["naive_render_ms"].get<double>(), harness::median_of(naive_ms)) << r["key"];
      EXPECT_LE(r["speedup_ci"][0].get<double>(), r["speedup"].get<double>());
      EXPECT_GE(r["speedup_ci"][1].get<double>(), r["speedup"].get<double>());
      if (r["structure"] == "naive") {
        EXPECT_DOUBLE_EQ(r["speedup"].get<double>(), 1.0);
        EXPECT_EQ(r["speedup_ci"], json::array({1.0, 1.0}));
      }
      if (threshold == 0.0) {
        EXPECT_EQ(r["remeasured"], 1) << r["key"];
        EXPECT_TRUE(r["noisy"].get<bool>()) << r["key"];  // still wider than 0
      }
    }
    EXPECT_TRUE(valid_against_schema(doc, dir)) << threshold;
    fs::remove(dir / "t.json");
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
  const int st = run_cli(tiny_sweep_args(dir, name),
                         {"ACCELBENCH_SWEEP_KILL_AFTER_ROWS=" + std::to_string(rows)});
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
  int st = run_cli(args, {});
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
  st = run_cli(args, {});
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

TEST(SweepIntegratorKnobs, EachSettingIsValidatedAgainstNaiveWithTheSameKnobs) {
  const fs::path dir = temp_dir("integrator_knobs");
  const auto d = harness::parse_sweep_definition(
      {{"name", "ik"},
       {"scenes", {"five"}},
       {"structures", {"naive", "bvh"}},
       {"integrator_knobs", json::array({{{"max_depth", {1, 4}}}, {{"spp", {2}}}})},
       {"resolution", "16x12"},
       {"repetitions", 1},
       {"warmup", 0}});
  harness::RunOptions o;
  o.out_path = (dir / "ik.json").string();
  o.jsonl_path = (dir / "ik.jsonl").string();
  o.progress = false;
  const harness::RunSummary summary = harness::run_sweep(d, o);
  EXPECT_TRUE(summary.complete);
  const json results = read_json(dir / "ik.json");
  ASSERT_EQ(results["rows"].size(), 6u);
  std::map<std::string, std::string> naive_hash;  // integrator params -> naive's image hash
  for (const auto& r : results["rows"]) {
    ASSERT_EQ(r["status"], "ok") << r.dump();
    ASSERT_TRUE(r.contains("integrator_params"));
    if (r["structure"] == "naive") naive_hash[r["integrator_params"].dump()] = r["image_hash"];
  }
  ASSERT_EQ(naive_hash.size(), 3u);
  EXPECT_NE(naive_hash["{\"max_depth\":1}"], naive_hash["{\"max_depth\":4}"]);  // glass and mirrors
  for (const auto& r : results["rows"]) {
    EXPECT_EQ(r["naive_image_hash"], naive_hash.at(r["integrator_params"].dump()));
    EXPECT_EQ(r["image_hash"], r["naive_image_hash"]);
  }
  EXPECT_TRUE(valid_against_schema(results, dir));
  fs::remove_all(dir);
}

TEST(SweepSpd, ValidatesAtAReducedResolutionAndClaimsNoSpeedup) {
  const fs::path dir = temp_dir("spd");
  // A tiny NFF scene: three spheres (one reflective) standing on a square polygon.
  std::ofstream(dir / "tiny.nff") << "b 0.1 0.2 0.5\n"
                                     "v\nfrom 3 2 2\nat 0 0 0\nup 0 0 1\nangle 45\nhither 0.01\n"
                                     "resolution 32 32\n"
                                     "l 4 3 5\nl -3 1 4\n"
                                     "f 1 0.8 0.6 0.7 0.3 20 0 1\n"
                                     "p 4\n3 3 -0.5\n-3 3 -0.5\n-3 -3 -0.5\n3 -3 -0.5\n"
                                     "f 0.9 0.9 0.9 0.5 0.5 3 0 1\n"
                                     "s 0 0 0 0.5\ns 0.8 0 0 0.25\ns 0 0.8 0 0.25\n";
  const std::vector<std::string> args = {"sweep", "--config", ACCELBENCH_SOURCE_DIR "/sweeps/quick.json",
                                         "--scenes", (dir / "tiny.nff").string(), "--accel", "naive,bvh,kdtree",
                                         "--spd", "--resolution", "24x20", "--validate-resolution", "8x6",
                                         "--repetitions", "1", "--warmup", "0",
                                         "--out", (dir / "spd.json").string(), "--quiet"};
  const int st = run_cli(args, {});
  ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << st;
  const json results = read_json(dir / "spd.json");
  EXPECT_TRUE(results["complete"].get<bool>());
  EXPECT_EQ(results["sweep"]["integrator"], "spd");
  EXPECT_EQ(results["sweep"]["validate_resolution"], "8x6");
  std::set<std::string> structures;
  for (const auto& row : results["rows"]) {
    EXPECT_EQ(row["status"], "ok") << row.dump();
    EXPECT_EQ(row["integrator"], "spd");
    structures.insert(row["structure"].get<std::string>());
    if (row["structure"] == "naive") {
      // Naive is rendered and timed at the validation resolution only, and its row says so.
      EXPECT_EQ(row["width"], 8);
      EXPECT_EQ(row["height"], 6);
      continue;
    }
    EXPECT_EQ(row["width"], 24);
    EXPECT_EQ(row["height"], 20);
    ASSERT_TRUE(row.contains("validated_at")) << row.dump();
    const json& v = row["validated_at"];
    EXPECT_EQ(v["width"], 8);
    EXPECT_EQ(v["height"], 6);
    EXPECT_EQ(v["image_hash"], v["naive_image_hash"]);
    EXPECT_EQ(v["rays"], v["naive_rays"]);
    EXPECT_EQ(v["rays"]["eye"], 9 * 7);  // SPD rays at pixel corners
    EXPECT_EQ(row["rays"]["eye"], 25 * 21);
    // Naive was not timed at 24x20: no speedup, and the reason.
    EXPECT_FALSE(row.contains("speedup"));
    EXPECT_FALSE(row.contains("naive_render_ms"));
    EXPECT_TRUE(row.contains("no_speedup_reason"));
  }
  EXPECT_EQ(structures, (std::set<std::string>{"naive", "bvh", "kdtree"}));
  EXPECT_TRUE(valid_against_schema(results, dir));

  // A bad integrator in a sweep file is refused; the one-line error names the JSON pointer.
  std::ofstream(dir / "bad.json") << json{{"scenes", {"five"}}, {"structures", {"naive"}}, {"integrator", "spd2"}}.dump();
  const std::string got = [&] {
    try {
      harness::load_sweep_file((dir / "bad.json").string());
    } catch (const SweepError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  }();
  EXPECT_NE(got.find("/integrator: unknown integrator \"spd2\" (known: whitted, spd"), std::string::npos) << got;
  EXPECT_EQ(got.find('\n'), std::string::npos);
  fs::remove_all(dir);
}

// Integrator knobs are sweep axes: each value crossed with every structure, naive measured once
// per value, rows carrying the knobs used and the integrator's statistics, and (with "images")
// each row's image. Bad values name their JSON pointer before anything runs.
TEST(SweepIntegratorKnobs, CrossesThemAndRecordsTheMaps) {
  const fs::path dir = temp_dir("photon");
  std::ofstream(dir / "p.json") << json{{"name", "p"},
                                        {"scenes", {"furnace"}},
                                        {"structures", {"naive", "bvh"}},
                                        {"integrator", "photon"},
                                        {"integrator_knobs", {{"k", {10, 30}}, {"global_photons", 2000}}},
                                        {"images", true},
                                        {"resolution", "8x6"},
                                        {"repetitions", 1},
                                        {"warmup", 0}}
                                       .dump();
  const auto d = harness::load_sweep_file((dir / "p.json").string());
  const auto configs = harness::expand(d);
  ASSERT_EQ(configs.size(), 4u);  // 2 values of k x (naive, bvh)
  std::set<std::string> settings;
  for (const auto& c : configs) settings.insert(c.structure + " " + c.integrator_params.dump());
  EXPECT_EQ(settings, (std::set<std::string>{"naive {\"global_photons\":2000,\"k\":10}",
                                             "naive {\"global_photons\":2000,\"k\":30}",
                                             "bvh {\"global_photons\":2000,\"k\":10}",
                                             "bvh {\"global_photons\":2000,\"k\":30}"}));
  const int st = run_cli({"sweep", "--config", (dir / "p.json").string(), "--out", (dir / "p-out.json").string(),
                          "--quiet"},
                         {});
  ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << st;
  const json results = read_json(dir / "p-out.json");
  ASSERT_EQ(results["rows"].size(), 4u);
  for (const auto& row : results["rows"]) {
    EXPECT_EQ(row["status"], "ok") << row.dump();
    EXPECT_EQ(row["integrator"], "photon");
    // Every knob used: the furnace scene's own (max_photon_depth 1000), the swept ones on top.
    const json& used = row["integrator_stats"]["counting"]["params"];
    EXPECT_EQ(used["k"], row["integrator_params"]["k"]);
    EXPECT_EQ(used["max_photon_depth"], 1000);
    const json& global = row["integrator_stats"]["counting"]["maps"]["global"];
    EXPECT_EQ(global["stored"], 2000);
    EXPECT_GT(global["build_ms"].get<double>(), 0.0);
    EXPECT_GT(row["integrator_stats"]["counting"]["gather"]["lookups"].get<int>(), 0);
    EXPECT_TRUE(row["integrator_stats"]["counting"]["gather"].contains("photons_visited_per_lookup"));
    EXPECT_TRUE(row["integrator_stats"]["timed"]["timings"].contains("photon_trace_ms"));
    ASSERT_TRUE(row.contains("image")) << row.dump();
    EXPECT_TRUE(fs::exists(row["image"].get<std::string>())) << row.dump();
    if (row["structure"] == "bvh") {
      EXPECT_EQ(row["image_hash"], row["naive_image_hash"]);
    }
  }
  EXPECT_TRUE(valid_against_schema(results, dir));

  std::ofstream(dir / "bad.json") << json{{"scenes", {"furnace"}}, {"structures", {"naive"}},
                                          {"integrator", "photon"}, {"integrator_knobs", {{"cone_k", {1, 0.5}}}}}
                                         .dump();
  const std::string got = [&] {
    try {
      harness::load_sweep_file((dir / "bad.json").string());
    } catch (const SweepError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  }();
  EXPECT_NE(got.find("/integrator_knobs/cone_k/1: photon: knob 'cone_k' must be in [1.0, "), std::string::npos)
      << got;
  fs::remove_all(dir);
}

}  // namespace
