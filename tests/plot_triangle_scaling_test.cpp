// scripts/plot_triangle_scaling.py draws the triangle scaling figure (PNG and SVG) and writes the
// numbers it plotted from bench_trace's Scaling benchmarks, leaving out a benchmark that failed
// and everything that is not a Scaling benchmark; a file with none gives one line and status 2.

#include "cli_run.h"
#include "test_files.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

int run_plot(const std::string& input, const fs::path& out, std::string& log) {
  const cli_run::CliRun r = cli_run::run(std::string(ACCELBENCH_PYTHON) + " " ACCELBENCH_SOURCE_DIR
                                         "/scripts/plot_triangle_scaling.py " + input + " --out " + out.string());
  log = r.output;
  return r.status;
}

using test_files::read;

TEST(PlotTriangleScaling, DrawsTheFigureAndWritesItsNumbers) {
  const fs::path dir = fs::temp_directory_path() / ("accelbench_plot_scaling_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string log;
  ASSERT_EQ(run_plot(ACCELBENCH_SOURCE_DIR "/tests/data/small_scaling.json", dir / "fig", log), 0) << log;
  EXPECT_EQ(read(dir / "fig.png").substr(1, 3), "PNG");
  EXPECT_NE(read(dir / "fig.svg").find("<svg"), std::string::npos);
  const nlohmann::json out = nlohmann::json::parse(read(dir / "fig.json"));
  EXPECT_EQ(out["context"]["isa"], "avx2");
  // Three scenes x two structures; the failed octree row and the Trace benchmark are left out.
  ASSERT_EQ(out["rows"].size(), 6u) << out.dump(1);
  bool seen = false;
  for (const nlohmann::json& r : out["rows"]) {
    EXPECT_NE(r["structure"], "octree");
    if (r["scene"] == "tess_L0" && r["structure"] == "embree_triangles") {
      seen = true;
      EXPECT_EQ(r["triangles"].get<double>(), 160000.0);
      EXPECT_DOUBLE_EQ(r["build_ms"].get<double>(), 19.2);
      EXPECT_DOUBLE_EQ(r["bytes_per_triangle"].get<double>(), 84.5);
      EXPECT_DOUBLE_EQ(r["camera_mrays_per_s"].get<double>(), 2.5);
      EXPECT_DOUBLE_EQ(r["incoherent_mrays_per_s"].get<double>(), 1.25);
    }
  }
  EXPECT_TRUE(seen);
  // The failed benchmark is named, on stderr and in the JSON.
  EXPECT_EQ(out["failed"]["Scaling/tess_L0/coherent/octree"], "validation failed");
  EXPECT_NE(log.find("left out, failed its check: Scaling/tess_L0/coherent/octree: validation failed"),
            std::string::npos)
      << log;
  fs::remove_all(dir);
}

TEST(PlotTriangleScaling, AFileWithoutScalingBenchmarksGivesOneLine) {
  const fs::path dir = fs::temp_directory_path() / ("accelbench_plot_scaling_none_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string log;
  EXPECT_EQ(run_plot(ACCELBENCH_SOURCE_DIR "/tests/data/small_bench_photon.json", dir / "fig", log), 2);
  EXPECT_EQ(log.rfind("plot_triangle_scaling: no Scaling benchmark in ", 0), 0u) << log;
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1) << log;
  EXPECT_FALSE(fs::exists(dir / "fig.png"));
  fs::remove_all(dir);
}

// scripts/triangle_scaling with ACCELBENCH_BUILD_DIR an absolute path (as a helper's own build
// folder is): it once looked for bench_trace under the repository even so. A scene already
// measured in --dir is not measured again, so the script goes straight to the figure, and exits 1
// because the file holds a benchmark that failed its check.
TEST(TriangleScalingScript, TakesAnAbsoluteBuildDirectory) {
#ifndef ACCELBENCH_BENCH_TRACE_DIR
  GTEST_SKIP() << "bench_trace is not built (ACCELBENCH_BENCHMARKS=OFF)";
#else
  const fs::path dir = fs::temp_directory_path() / ("accelbench_scaling_script_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(ACCELBENCH_SOURCE_DIR "/tests/data/small_scaling.json", dir / "tess_L0.json");
  const fs::path build = fs::absolute(fs::path(ACCELBENCH_BENCH_TRACE_DIR) / "..");
  const cli_run::CliRun r = cli_run::run("cd " + dir.string() + " && ACCELBENCH_BUILD_DIR=" + build.string() +
                                         " " ACCELBENCH_SOURCE_DIR "/scripts/triangle_scaling --dir " +
                                         dir.string() + " --scenes tess_L0 --out " + (dir / "fig").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_EQ(r.output.find("not found"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("tess_L0 already measured"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir / "fig.png")) << r.output;
  fs::remove_all(dir);
#endif
}

}  // namespace
