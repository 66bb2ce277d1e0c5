// Running sweeps end to end through `accelbench sweep`: listing a shard's keys, interleaved
// timing rounds against naive, integrator knobs as axes, and the SPD mode.

#include "harness/bootstrap.h"
#include "harness/sweep_definition.h"
#include "harness/sweep_jsonl.h"
#include "harness/sweep_machine.h"
#include "harness/sweep_runner.h"
#include "harness/sweep_stats.h"

#include "cli_run.h"

#include "scenes_gen/generators.h"
#include "scenes_gen/mesh_scenes.h"
#include "accel/accel.h"

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

// Every configuration of a scene, naive included, is timed once per round; speedups
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

// Embree's own triangles answer with Embree's routine, so a sweep checks them against naive
// within the peers' tolerance (tracer::kPeerPixelsOffShare), not bit for bit; the robust build
// differs from naive in a few pixels of the bunny at 32x24, which failed it before.
TEST(SweepPeers, EmbreesOwnTrianglesAreCheckedWithinTheirTolerance) {
  const accel::StructureInfo* peer = accel::find_structure("embree_triangles");
  if (!peer || !peer->built) GTEST_SKIP() << "Embree is not built";
  try {
    scenes_gen::model_path("bunny");
  } catch (const scenes_gen::GenError& e) {
    GTEST_SKIP() << e.what();
  }
  const fs::path dir = temp_dir("peers");
  const auto d = harness::parse_sweep_definition(
      {{"name", "peers"},
       {"scenes", {{{"generator", "mesh"}, {"model", "bunny"}, {"name", "bunny"}}}},
       {"structures", {"bvh", "embree_triangles", {{"name", "embree_triangles"}, {"robust", true}}}},
       {"resolution", "40x30"},
       {"validate_resolution", "32x24"},
       {"remeasure", 0},
       {"repetitions", 1},
       {"warmup", 0}});
  harness::RunOptions o;
  o.out_path = (dir / "peers.json").string();
  o.jsonl_path = (dir / "peers.jsonl").string();
  o.progress = false;
  EXPECT_TRUE(harness::run_sweep(d, o).complete);
  const json results = read_json(dir / "peers.json");
  ASSERT_EQ(results["rows"].size(), 3u);  // naive is the reference, not a row (not listed)
  for (const auto& r : results["rows"]) {
    EXPECT_EQ(r["status"], "ok") << r.dump();
    if (r["structure"] == "bvh") EXPECT_EQ(r["validated_at"]["image_hash"], r["validated_at"]["naive_image_hash"]);
    else
      std::printf("%s %s: %s naive's image at 32x24\n", r["structure"].get<std::string>().c_str(), r["params"].dump().c_str(),
                  r["validated_at"]["image_hash"] == r["validated_at"]["naive_image_hash"] ? "equal to" : "within tolerance of");
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
  const int st = run_cli(args);
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
                          "--quiet"});
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
