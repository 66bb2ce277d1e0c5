// scripts/plot.py draws every figure, PNG and SVG, from the committed small results file, and
// fails with one line on a file that is not a results file; a fronts point the reference cannot
// resolve is drawn hollow.

#include "harness/fronts.h"
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
  const std::string cmd = std::string(ACCELBENCH_PYTHON) + " " ACCELBENCH_SOURCE_DIR "/scripts/plot.py " + input +
                          " --out " + out.string() + " > " + log.string() + " 2>&1";
  const int st = std::system(cmd.c_str());
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

using test_files::read;

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

  // The small fronts file predates error intervals: every point is drawn filled.
  EXPECT_EQ(read(dir / "fronts" / "fronts_five.svg").find("id=\"unresolved\""), std::string::npos);

  std::ofstream(dir / "not_results.json") << "{\"rows\": []}";
  EXPECT_EQ(run_plot((dir / "not_results.json").string(), dir / "fig2", dir / "log2.txt"), 1);
  EXPECT_NE(read(dir / "log2.txt").find("/format: not an accelbench results file"), std::string::npos);
  fs::remove_all(dir);
}

/// The number of markers drawn hollow in an SVG of plot.py: the "fill: none" styles inside its
/// groups with id "unresolved" (each ends where the next artist's group begins).
std::size_t hollow_markers(const std::string& svg) {
  std::size_t count = 0;
  for (std::size_t at = svg.find("<g id=\"unresolved\">"); at != std::string::npos;
       at = svg.find("<g id=\"unresolved\">", at + 1)) {
    const std::size_t end = svg.find("<g id=\"", at + 1);
    const std::string group = svg.substr(at, end == std::string::npos ? std::string::npos : end - at);
    EXPECT_EQ(group.find("fill: #"), std::string::npos) << "a filled marker among the unresolved";
    for (std::size_t k = group.find("fill: none"); k != std::string::npos; k = group.find("fill: none", k + 1)) ++count;
  }
  return count;
}

// Raise the max_depth front's floor of the small fronts file to 0.002 RMSE: depths 4 and 64
// (RMSE 0.0014 and 3.7e-5) become unresolved, depth 1 (0.12) and the spp points stay resolved.
// Annotated by the harness, the figure draws exactly those two hollow, with error bars and the
// legend saying what hollow means.
TEST(Plot, UnresolvedFrontPointsAreDrawnHollow) {
  const fs::path dir = fs::temp_directory_path() / ("accelbench_plot_hollow_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ifstream in(ACCELBENCH_SOURCE_DIR "/tests/data/small_fronts.json");
  nlohmann::json doc = nlohmann::json::parse(in);
  for (auto& row : doc["rows"])
    if (row["front"] == "max_depth") row["reference"]["floor"]["rmse"] = 0.002;
  harness::annotate_fronts(doc);
  std::size_t unresolved = 0;
  for (const auto& row : doc["rows"]) unresolved += !row["resolved"].get<bool>();
  ASSERT_EQ(unresolved, 2u);
  std::ofstream(dir / "fronts.json") << doc.dump();
  ASSERT_EQ(run_plot((dir / "fronts.json").string(), dir / "out", dir / "log.txt"), 0) << read(dir / "log.txt");
  const std::string svg = read(dir / "out" / "fronts_five.svg");
  EXPECT_EQ(hollow_markers(svg), 2u);
  EXPECT_NE(svg.find("hollow: unresolved (interval reaches the reference floor)"), std::string::npos);
  EXPECT_NE(svg.find("error interval (seeds and floor)"), std::string::npos);
  EXPECT_NE(svg.find("reference floor"), std::string::npos);
  // All resolved again: nothing hollow.
  for (auto& row : doc["rows"]) row["reference"]["floor"]["rmse"] = 0.0;
  harness::annotate_fronts(doc);
  std::ofstream(dir / "fronts.json") << doc.dump();
  ASSERT_EQ(run_plot((dir / "fronts.json").string(), dir / "out", dir / "log.txt"), 0) << read(dir / "log.txt");
  EXPECT_EQ(hollow_markers(read(dir / "out" / "fronts_five.svg")), 0u);
  fs::remove_all(dir);
}

}  // namespace
