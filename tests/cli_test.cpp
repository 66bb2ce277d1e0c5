// The accelbench command line, run as a user runs it: sizes, determinism, and one-line errors.

#include "cli_run.h"

#include "tracer/image.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

using cli_run::CliRun;

using cli_run::accelbench;

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("accelbench_cli_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(Cli, RefractionSceneRendersAtTheRequestedSizeBitIdenticalOnOneAndTwoThreads) {
  const std::string scene = path("refraction.json");
  const CliRun gen = accelbench("gen refraction -o " + scene);
  ASSERT_EQ(gen.status, 0) << gen.output;
  const CliRun one =
      accelbench("render " + scene + " --resolution 48x32 --threads 1 --accel naive -o " +
                 path("one.png") + " --pfm " + path("one.pfm") + " --stats " + path("one.json"));
  ASSERT_EQ(one.status, 0) << one.output;
  const CliRun two = accelbench(
      "render " + scene + " --resolution 48x32 --threads 2 --accel naive --pfm " + path("two.pfm"));
  ASSERT_EQ(two.status, 0) << two.output;
  EXPECT_NE(one.output.find("rays/s"), std::string::npos) << one.output;
  EXPECT_NE(one.output.find("12 triangles, 288 boxes, 1 plane; 2 lights"), std::string::npos)
      << one.output;

  const tracer::Image a = tracer::Image::read_pfm(path("one.pfm"));
  const tracer::Image b = tracer::Image::read_pfm(path("two.pfm"));
  EXPECT_EQ(a.width(), 48);
  EXPECT_EQ(a.height(), 32);
  EXPECT_EQ(a.content_hash(), b.content_hash());
  EXPECT_TRUE(fs::file_size(path("one.png")) > 100);

  std::ifstream in(path("one.json"));
  const nlohmann::json stats = nlohmann::json::parse(in);
  EXPECT_EQ(stats["resolution"], nlohmann::json::array({48, 32}));
  EXPECT_EQ(stats["accel"], "naive");
  EXPECT_EQ(stats["image_hash"], tracer::hash_hex(a.content_hash()));
  EXPECT_EQ(stats["rays"]["eye"], 48 * 32 * 4);
  EXPECT_GT(stats["traversal"]["prims_tested"].get<double>(), 0.0);
}

TEST_F(Cli, BadSceneGivesOneLineNamingThePathAndExitsNonZero) {
  const std::string scene = path("bad.json");
  std::ofstream(scene) << R"({"materials": [{"name": "m", "type": "diffuse"}],
                              "spheres": [{"center": [0, 0, 0], "radius": -1, "material": "m"}]})";
  const CliRun r = accelbench("render " + scene + " -o " + path("x.png"));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.output, "accelbench: " + scene + ": /spheres/0/radius: must be > 0, got -1\n");
}

TEST_F(Cli, BadFlagsGiveOneLineAndExitNonZero) {
  const std::string scene = path("five.json");
  ASSERT_EQ(accelbench("gen five -o " + scene).status, 0);
  const struct {
    std::string args;
    std::string message;
  } cases[] = {
      {"render " + scene + " --resolution 64",
       "accelbench: --resolution: expected WIDTHxHEIGHT with each in [1, 65536], e.g. 640x480, got "
       "'64'\n"},
      {"render " + scene + " --accel octree2",
       "accelbench: --accel: unknown structure 'octree2' (known: "},
      {"render " + scene + " --accel naive --max-depth 3", "accelbench: naive: "},
      {"render " + scene + " --max-memory 12Q",
       "accelbench: --max-memory: expected a byte count such as 1000000, 512M or 2G, got '12Q'\n"},
      {"render " + scene + " -o out.jpg",
       "accelbench: -o: expected a .png file name, got 'out.jpg'\n"},
      {"render " + path("missing.json"),
       "accelbench: " + path("missing.json") + ": cannot open: No such file or directory\n"},
      {"gen nosuch -o " + path("x.json"),
       "accelbench: unknown generator 'nosuch' (known: refraction, spheres8000, five, random"},
      {"gen five --count 3 -o " + path("x.json"),
       "accelbench: five: takes no count (it has a fixed size)\n"},
      {"render " + scene + " --threads -2", "accelbench: --threads: "},
      {"render " + scene + " --integrator phong",
       "accelbench: --integrator: unknown integrator 'phong' (known: whitted, spd"},
      {"render " + scene + " --spd --integrator whitted",
       "accelbench: --spd: is --integrator spd, but --integrator whitted was given\n"},
      {"frobnicate", "accelbench: "},
  };
  for (const auto& c : cases) {
    const CliRun r = accelbench(c.args);
    EXPECT_NE(r.status, 0) << c.args;
    EXPECT_EQ(r.output.rfind(c.message, 0), 0u) << c.args << "\n got: " << r.output;
    EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << "not one line: " << r.output;
  }
}

TEST_F(Cli, HelpOnEverySubcommand) {
  for (const char* sub : {"", "render ", "gen "}) {
    const CliRun r = accelbench(std::string(sub) + "--help");
    EXPECT_EQ(r.status, 0) << sub;
    EXPECT_NE(r.output.find("Usage"), std::string::npos) << sub;
  }
}

TEST_F(Cli, RandomGeneratorTakesAnyCountIncludingZero) {
  const CliRun zero = accelbench("gen random --count 0 -o " + path("r0.json"));
  ASSERT_EQ(zero.status, 0) << zero.output;
  EXPECT_NE(zero.output.find("no primitives"), std::string::npos) << zero.output;
  const CliRun render = accelbench("render " + path("r0.json") + " --resolution 8x8 --accel naive");
  EXPECT_EQ(render.status, 0) << render.output;
  const CliRun some = accelbench("gen random --count 123 --seed 9 -o " + path("r1.json"));
  EXPECT_NE(some.output.find("123 spheres"), std::string::npos) << some.output;
}

// A model converted to a bare file name in the working folder (no folder part, as a user types
// it): the scene is written, refers to the model beside it, and renders. std::filesystem::absolute
// refuses the empty folder of a bare name, which once failed this with a filesystem error.
TEST_F(Cli, ConvertToABareNameInTheWorkingFolder) {
  std::ofstream(path("tri.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::string in_dir = "cd " + dir_.string() + " && ";
  const CliRun convert = cli_run::run(in_dir + ACCELBENCH_CLI + " convert tri.obj -o tri.json");
  ASSERT_EQ(convert.status, 0) << convert.output;
  std::ifstream saved(path("tri.json"));
  const nlohmann::json doc = nlohmann::json::parse(saved);
  EXPECT_EQ(doc["meshes"][0]["file"], "tri.obj");
  const CliRun render = cli_run::run(in_dir + ACCELBENCH_CLI + " render tri.json --resolution 8x8 -o tri.png");
  EXPECT_EQ(render.status, 0) << render.output;
  EXPECT_TRUE(fs::exists(path("tri.png")));
}

// The photon integrator from the command line: the scene's knobs, --param on top, one-line errors
// naming the knob for bad values, and --stats recording the maps.
TEST_F(Cli, PhotonKnobsFromSceneAndFlagsAndBadOnesNameTheKnob) {
  const std::string scene = path("furnace.json");
  ASSERT_EQ(accelbench("gen furnace -o " + scene).status, 0);
  const CliRun ok = accelbench("render " + scene +
                               " --resolution 8x8 --param global_photons=3000 --param filter=box "
                               "--stats " + path("f.json"));
  ASSERT_EQ(ok.status, 0) << ok.output;
  EXPECT_NE(ok.output.find("integrator photon"), std::string::npos) << ok.output;
  EXPECT_NE(ok.output.find("caustic map skipped: no specular surface"), std::string::npos) << ok.output;
  std::ifstream in(path("f.json"));
  const nlohmann::json stats = nlohmann::json::parse(in);
  EXPECT_EQ(stats["integrator"], "photon");
  EXPECT_EQ(stats["integrator_params"]["global_photons"], 3000);  // --param
  EXPECT_EQ(stats["integrator_params"]["k"], 100);                // the scene's
  EXPECT_EQ(stats["integrator_params"]["filter"], "box");
  EXPECT_EQ(stats["integrator_stats"]["timed"]["maps"]["global"]["stored"], 3000);
  EXPECT_GT(stats["integrator_stats"]["counting"]["gather"]["photons_visited_per_lookup"].get<double>(), 0.0);
  EXPECT_GT(stats["rays"]["photon"].get<double>(), 0.0);

  const struct {
    std::string args;
    std::string message;
  } cases[] = {
      {"--param global_photons=0", "accelbench: --param: photon: knob 'global_photons' must be in [1, "},
      {"--param caustic_photons=-3", "accelbench: --param: photon: knob 'caustic_photons' must be in [1, "},
      {"--param k=0", "accelbench: --param: photon: knob 'k' must be in [1, "},
      {"--param cone_k=0.5", "accelbench: --param: photon: knob 'cone_k' must be in [1.0, "},
      {"--param max_radius=0", "accelbench: --param: photon: knob 'max_radius' must be in (0.0, 3e+38] or \"auto\", got 0"},
      {"--param max_radius=-2", "accelbench: --param: photon: knob 'max_radius' must be in (0.0, 3e+38] or \"auto\", got -2"},
      {"--param global_photons=100000000 --max-memory 1M",
       "accelbench: photon: knob 'global_photons' = 100000000 needs "},
      {"--param kk=1", "accelbench: --param: photon: unknown knob 'kk'"},
      {"--param k", "accelbench: --param: expected NAME=VALUE, got 'k'"},
      {"--integrator whitted --param k=3", "accelbench: --param: whitted: unknown knob 'k'"},
  };
  for (const auto& c : cases) {
    const CliRun r = accelbench("render " + scene + " --resolution 8x8 " + c.args);
    EXPECT_NE(r.status, 0) << c.args;
    EXPECT_EQ(r.output.rfind(c.message, 0), 0u) << c.args << "\n got: " << r.output;
    EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << "not one line: " << r.output;
  }
  // A bad knob in the scene names the scene and its JSON pointer.
  std::ofstream(path("bad.json")) << R"({"integrator": {"name": "photon", "k": 0},
      "materials": [{"name": "m", "type": "diffuse"}], "spheres": [{"center": [0, 0, -3], "radius": 1, "material": "m"}]})";
  const CliRun bad = accelbench("render " + path("bad.json") + " --resolution 8x8");
  EXPECT_NE(bad.status, 0);
  EXPECT_EQ(bad.output.rfind("accelbench: " + path("bad.json") + ": /integrator: photon: knob 'k'", 0), 0u)
      << bad.output;
}

}  // namespace
