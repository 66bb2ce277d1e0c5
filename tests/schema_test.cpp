// The results file validates against results/schema/results.schema.json (checked by Python's
// jsonschema, draft 2020-12), and the schema rejects files that break its rules.

#include "harness/sweep_definition.h"
#include "harness/sweep_results.h"
#include "harness/sweep_runner.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

const char* kValidator = R"(import json, sys
import jsonschema
schema = json.load(open(sys.argv[1]))
jsonschema.Draft202012Validator.check_schema(schema)
errors = list(jsonschema.Draft202012Validator(schema).iter_errors(json.load(open(sys.argv[2]))))
for e in errors[:5]:
    print("/" + "/".join(str(p) for p in e.absolute_path) + ": " + e.message[:200], file=sys.stderr)
sys.exit(1 if errors else 0)
)";

class SchemaTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("accelbench_schema_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "validate.py") << kValidator;
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// True when `doc` validates against the schema.
  bool valid(const json& doc) {
    const fs::path file = dir_ / "doc.json";
    std::ofstream(file) << doc.dump();
    const std::string cmd = std::string(ACCELBENCH_PYTHON) + " " + (dir_ / "validate.py").string() + " " +
                            ACCELBENCH_SOURCE_DIR "/results/schema/results.schema.json " + file.string();
    return std::system(cmd.c_str()) == 0;
  }

  fs::path dir_;
};

TEST_F(SchemaTest, TinySweepRowsValidateAndBrokenOnesDoNot) {
  const auto d = harness::parse_sweep_definition(
      {{"name", "tiny-schema"},
       {"scenes", {"random:40", "five"}},
       {"structures",
        {"naive", {{"name", "octree"}, {"max_depth", {2, 70}}}, "kdtree", "bvh", "embree"}},
       {"resolution", "16x12"},
       {"repetitions", 2},
       {"warmup", 1}});
  harness::RunOptions o;
  o.out_path = (dir_ / "tiny.json").string();
  o.jsonl_path = (dir_ / "tiny.jsonl").string();
  o.progress = false;
  const auto summary = harness::run_sweep(d, o);
  EXPECT_TRUE(summary.complete);
  const json doc = harness::read_results_file(o.out_path);

  std::size_t ok = 0, failed = 0;
  for (const auto& r : doc["rows"]) {
    ok += r["status"] == "ok";
    failed += r["status"] == "failed";
  }
  EXPECT_GE(ok, 6u);
  EXPECT_GE(failed, 2u);  // max_depth 70 is an invalid knob on both scenes
  ASSERT_TRUE(valid(doc));

  json broken = doc;
  broken["machine"].erase("cpu_model");
  EXPECT_FALSE(valid(broken)) << "machine without cpu_model";

  broken = doc;
  for (auto& r : broken["rows"])
    if (r["status"] == "ok") {
      r.erase("render_ms");
      break;
    }
  EXPECT_FALSE(valid(broken)) << "ok row without timings";

  broken = doc;
  for (auto& r : broken["rows"])
    if (r["status"] == "failed") {
      r["speedup"] = 2.0;
      break;
    }
  EXPECT_FALSE(valid(broken)) << "failed row carrying a speed";

  broken = doc;
  broken["rows"][0]["status"] = "fine";
  EXPECT_FALSE(valid(broken)) << "unknown status";
}

TEST_F(SchemaTest, CommittedResultsFilesValidate) {
  std::ifstream in(ACCELBENCH_SOURCE_DIR "/tests/data/small_results.json");
  ASSERT_TRUE(in) << "tests/data/small_results.json missing";
  EXPECT_TRUE(valid(json::parse(in)));
}

}  // namespace
