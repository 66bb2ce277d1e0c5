// The stability suite (harness/stability.h): its variants move and scale a scene as a user would,
// and `accelbench stability` runs as a user runs it, its JSON checked against
// results/schema/stability.schema.json (Python's jsonschema, draft 2020-12).

#include "cli_run.h"

#include "harness/stability.h"
#include "harness/stability_variants.h"
#include "scenes_gen/generators.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using cli_run::accelbench;

class Stability : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("accelbench_stability_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    std::ofstream(dir_ / "validate.py")
        << "import json, sys\nimport jsonschema\n"
           "schema = json.load(open(sys.argv[1]))\n"
           "jsonschema.Draft202012Validator.check_schema(schema)\n"
           "errors = list(jsonschema.Draft202012Validator(schema).iter_errors(json.load(open(sys.argv[2]))))\n"
           "for e in errors[:3]:\n"
           "    print('/' + '/'.join(str(p) for p in e.absolute_path) + ': ' + e.message[:200], file=sys.stderr)\n"
           "sys.exit(1 if errors else 0)\n";
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  /// True when `doc` validates against the stability schema.
  bool valid(const json& doc) {
    std::ofstream(dir_ / "doc.json") << doc.dump();
    const cli_run::CliRun r = cli_run::run(std::string(ACCELBENCH_PYTHON) + " " + path("validate.py") +
                                           " " ACCELBENCH_SOURCE_DIR "/results/schema/stability.schema.json " +
                                           path("doc.json"));
    if (r.status != 0) std::cerr << r.output;
    return r.status == 0;
  }
  fs::path dir_;
};

TEST_F(Stability, CommandRunsChecksEveryStructureAndWritesJsonThatFollowsTheSchema) {
  ASSERT_EQ(accelbench("gen five -o " + path("five.json")).status, 0);
  const cli_run::CliRun r = accelbench(
      "stability " + path("five.json") +
      " --resolution 32x24 --threads 2 --accel bvh,kdtree:split=sah,octree:placement=every_level"
      " --variants base,translate_x_1e4,scale_1e-3,camera_-y,duplicated,touching,snapped --out " +
      path("out/s.json") + " --images " + path("img"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("every structure equals naive on every variant"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("translate_x_1e4"), std::string::npos) << r.output;

  std::ifstream in(path("out/s.json"));
  const json doc = json::parse(in);
  ASSERT_TRUE(valid(doc));
  EXPECT_EQ(doc["failures"], 0);
  // In catalogue order: base, translate, scale, camera, snapped, duplicated, touching.
  ASSERT_EQ(doc["variants"].size(), 7u);
  EXPECT_EQ(doc["variants"][0]["name"], "base");
  for (const json& v : doc["variants"]) {
    SCOPED_TRACE(v["name"].get<std::string>());
    ASSERT_EQ(v["structures"].size(), 3u);
    for (const json& s : v["structures"]) {
      EXPECT_TRUE(s["equal_image"].get<bool>()) << s["label"];
      EXPECT_TRUE(s["equal_rays"].get<bool>()) << s["label"];
      EXPECT_EQ(s["image_hash"], v["float"]["image_hash"]);
    }
    EXPECT_EQ(v["float"]["non_finite"], 0);
    EXPECT_EQ(v["double"]["non_finite"], 0);
    EXPECT_GT(v["float"]["rays"]["eye_hits"].get<int>(), 100);
    // Float and double agree on most of the image (five has no tiny features at this size).
    EXPECT_LT(v["float_vs_double"]["fraction_off"].get<double>(), 0.05);
  }
  // The base compared with itself is exact; the moved scenes are compared with the base.
  EXPECT_EQ(doc["variants"][0]["float"]["vs_base"]["pixels_off"], 0);
  EXPECT_EQ(doc["variants"][1]["name"], "translate_x_1e4");
  EXPECT_FALSE(doc["variants"][1]["float"]["ray_change"].is_null());
  EXPECT_FALSE(doc["variants"][1]["meets_target"].is_null());
  // The camera variant changes the picture: no comparison with the base.
  EXPECT_TRUE(doc["variants"][3]["float"]["vs_base"].is_null());
  // Duplicated primitives double the count and leave the image as it was.
  EXPECT_EQ(doc["variants"][5]["primitives"].get<int>(), 2 * doc["variants"][0]["primitives"].get<int>());
  EXPECT_EQ(doc["variants"][5]["float"]["vs_base"]["pixels_off"], 0);
  EXPECT_TRUE(fs::exists(path("img/translate_x_1e4_float.png")));
  EXPECT_TRUE(fs::exists(path("img/translate_x_1e4_double.png")));

  // The schema rejects what breaks it.
  json broken = doc;
  broken["variants"][0]["structures"][0]["equal_image"] = "yes";
  EXPECT_FALSE(valid(broken));
  broken = doc;
  broken.erase("failures");
  EXPECT_FALSE(valid(broken));
}

// The integrator's knobs reach every render (the triangle routine: a row of its own per routine
// in scripts/run), and the results say which were given.
TEST_F(Stability, IntegratorKnobsReachEveryRenderAndAreRecorded) {
  ASSERT_EQ(accelbench("gen cornell -o " + path("cornell.json")).status, 0);
  for (const char* routine : {"watertight", "moller"}) {
    const std::string out = path(std::string(routine) + ".json");
    const cli_run::CliRun r = accelbench("stability " + path("cornell.json") + " --param triangle=" + routine +
                                         " --resolution 32x24 --threads 2 --accel bvh8 --variants base,translate_x_1e2 --out " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find(std::string("{\"triangle\":\"") + routine + "\"}"), std::string::npos) << r.output;
    std::ifstream in(out);
    const json doc = json::parse(in);
    ASSERT_TRUE(valid(doc));
    EXPECT_EQ(doc["integrator_params"], json({{"triangle", routine}}));
    EXPECT_EQ(doc["failures"], 0);
  }
  for (const auto& [flag, names] : {std::pair<std::string, std::string>{"--param precision=double", "precision"},
                                    {"--param triangle=fast", "triangle"},
                                    {"--param nosuch=1", "nosuch"}}) {
    SCOPED_TRACE(flag);
    const cli_run::CliRun r = accelbench("stability " + path("cornell.json") + " " + flag);
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.output.find(names), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
}

TEST_F(Stability, BadInputIsOneLineAndAFailingExit) {
  ASSERT_EQ(accelbench("gen five -o " + path("five.json")).status, 0);
  for (const auto& [flags, names] :
       {std::pair<std::string, std::string>{"--variants nosuch", "--variants"},
        {"--accel nosuch", "--accel"},
        {"--accel naive", "--accel"},
        {"--accel kdtree:split", "--accel"},
        {"--resolution 0x5", "--resolution"},
        {"--out x.txt", "--out"}}) {
    SCOPED_TRACE(flags);
    const cli_run::CliRun r = accelbench("stability " + path("five.json") + " " + flags);
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.output.find(names), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
  const cli_run::CliRun missing = accelbench("stability " + path("missing.json"));
  EXPECT_NE(missing.status, 0);
  EXPECT_EQ(std::count(missing.output.begin(), missing.output.end(), '\n'), 1) << missing.output;
}

TEST(StabilityVariants, MoveAndScaleEverythingTogether) {
  const tracer::Scene five = scenes_gen::generate("five", {});
  const auto variants = harness::select_variants("translate_diag_1e5,scale_1e-6", "--variants");
  ASSERT_EQ(variants.size(), 3u);  // base first
  const tracer::Scene moved = harness::make_variant(five, variants[1]);
  EXPECT_NEAR(double(moved.camera.position.x), double(five.camera.position.x) + 1e5, 0.01);
  EXPECT_NEAR(double(moved.camera.position.y), double(five.camera.position.y) - 1e5, 0.01);
  EXPECT_NEAR(double(moved.lights[0].position.z), double(five.lights[0].position.z) + 1e5, 0.01);
  EXPECT_NEAR(double(moved.geometry.spheres[0].center.x),
              double(five.geometry.spheres[0].center.x) + 1e5, 0.01);
  const tracer::Scene small = harness::make_variant(five, variants[2]);
  EXPECT_NEAR(double(small.geometry.spheres[0].radius), 1e-6 * double(five.geometry.spheres[0].radius),
              1e-12);
  // "quick" and "all" expand; an unknown name is refused naming the flag.
  EXPECT_EQ(harness::select_variants("quick", "--v").size(), 6u);
  EXPECT_EQ(harness::select_variants("all", "--v").size(), 34u);  // 1 + 6 + 6 + 12 + 6 + 3
  EXPECT_THROW(harness::select_variants("scale_1e9", "--v"), std::runtime_error);
}

}  // namespace
