// scripts/plot_knn.py draws the kNN figure, PNG and SVG, and prints its tables from a small
// bench_photon output, and fails with one line on a file that is not one.

#include "test_files.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

int run_plot(const std::string& input, const fs::path& out, const fs::path& log) {
  std::string cmd = ACCELBENCH_PYTHON " " ACCELBENCH_SOURCE_DIR "/scripts/plot_knn.py ";
  cmd.append(input).append(" --out ").append(out.string()).append(" > ").append(log.string()).append(" 2>&1");
  const int st = std::system(cmd.c_str());
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

using test_files::read;

TEST(PlotKnn, DrawsTheFigureAndTablesFromASmallRun) {
  const fs::path dir = fs::temp_directory_path() / ("accelbench_plot_knn_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  ASSERT_EQ(run_plot(ACCELBENCH_SOURCE_DIR "/tests/data/small_bench_photon.json", dir / "fig", dir / "log.txt"), 0)
      << read(dir / "log.txt");
  const std::string png = read(dir / "fig" / "knn_queries.png");
  ASSERT_GT(png.size(), 10000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_NE(read(dir / "fig" / "knn_queries.svg").find("<svg"), std::string::npos);
  const std::string log = read(dir / "log.txt");
  EXPECT_NE(log.find("| 10,000 | 8 |"), std::string::npos) << log;
  EXPECT_NE(log.find("| 10,000 | balanced | 1 |"), std::string::npos) << log;

  std::ofstream(dir / "other.json") << "{\"rows\": []}";
  EXPECT_EQ(run_plot((dir / "other.json").string(), dir / "fig2", dir / "log2.txt"), 1);
  EXPECT_EQ(read(dir / "log2.txt"),
            "plot_knn: " + (dir / "other.json").string() +
                ": not a Google Benchmark JSON file (no 'benchmarks')\n");
  EXPECT_EQ(run_plot((dir / "missing.json").string(), dir / "fig3", dir / "log3.txt"), 1);
  EXPECT_NE(read(dir / "log3.txt").find("missing.json: cannot read"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
