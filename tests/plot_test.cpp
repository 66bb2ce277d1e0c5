// scripts/plot.py draws every figure, PNG and SVG, from the committed small results file, and
// fails with one line on a file that is not a results file.

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

int run_plot(const std::string& input, const fs::path& out, const fs::path& log) {
  const std::string cmd = std::string(ACCELBENCH_PYTHON) + " " ACCELBENCH_SOURCE_DIR "/scripts/plot.py " + input +
                          " --out " + out.string() + " > " + log.string() + " 2>&1";
  const int st = std::system(cmd.c_str());
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(Plot, DrawsEveryFigureFromTheSmallResultsFile) {
  const fs::path dir = fs::temp_directory_path() / ("accelbench_plot_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  ASSERT_EQ(run_plot(ACCELBENCH_SOURCE_DIR "/tests/data/small_results.json", dir / "fig", dir / "log.txt"), 0)
      << read(dir / "log.txt");
  for (const char* name :
       {"paper_speedup", "heatmap_render_ms", "heatmap_nodes_per_ray", "scaling", "build_vs_trace"}) {
    const std::string png = read(dir / "fig" / (std::string(name) + ".png"));
    ASSERT_GT(png.size(), 10000u) << name;
    EXPECT_EQ(png.substr(1, 3), "PNG") << name;
    const std::string svg = read(dir / "fig" / (std::string(name) + ".svg"));
    EXPECT_NE(svg.find("<svg"), std::string::npos) << name;
  }
  // The speedup table beside the paper's figures goes to stdout.
  const std::string log = read(dir / "log.txt");
  EXPECT_NE(log.find("| spheres8000 |"), std::string::npos) << log;
  EXPECT_NE(log.find("| 3.8 |"), std::string::npos) << log;

  // A fronts results file (accelbench fronts) gives one speed/accuracy figure per scene, alone or
  // beside sweep results.
  ASSERT_EQ(run_plot(ACCELBENCH_SOURCE_DIR "/tests/data/small_fronts.json", dir / "fronts", dir / "log3.txt"), 0)
      << read(dir / "log3.txt");
  const std::string fronts_png = read(dir / "fronts" / "fronts_five.png");
  ASSERT_GT(fronts_png.size(), 10000u);
  EXPECT_EQ(fronts_png.substr(1, 3), "PNG");
  EXPECT_NE(read(dir / "fronts" / "fronts_five.svg").find("<svg"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "fronts" / "paper_speedup.png"));

  std::ofstream(dir / "not_results.json") << "{\"rows\": []}";
  EXPECT_EQ(run_plot((dir / "not_results.json").string(), dir / "fig2", dir / "log2.txt"), 1);
  EXPECT_NE(read(dir / "log2.txt").find("/format: not an accelbench results file"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
