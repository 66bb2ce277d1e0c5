#include "tracer/nff.h"
#include "test_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

namespace {

using tracer::load_nff;
using tracer::Scene;
using tracer::SceneError;
using tracer::Vec3;

Scene parse(const std::string& text) {
  std::istringstream in(text);
  return load_nff(in, "t.nff");
}

/// The one-line error that parsing `text` raises, or "" when it parses.
std::string nff_error(const std::string& text) {
  try {
    parse(text);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

// Seven lines: the broken entity in each corpus case sits on line 8.
const std::string kView =
    "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 64 48\n";

TEST(Nff, EveryConstruct) {
  const Scene s = parse(
      "# comment line\n"
      "b 0.1 0.2 0.3\n"  // b before v, as in every SPD file
      "v\n"
      "from 2 0 0   # trailing comment\n"
      "at 0 0 0\n"
      "up 1 0 1\n"  // not perpendicular to the view
      "angle 45\n"
      "hither 0.01\n"
      "resolution 32 16\n"
      "l 1 2 3\n"  // no colour
      "l 4 5 6 0.5 0.25 1\n"
      "f 1 0.5 0 0.8 0.2 30 0 0\n"  // ior 0 on an opaque material
      "s 0 0 0 0.5\n"
      "s 1 1 1 -2\n"
      "c 0 0 0 0.2 0 0 1 0.1\n"  // cone on one line
      "c 1 0 0 0.3\n"
      "  1 0 2\n"
      "  0.3\n"  // cylinder over several lines
      "f 1 1 1 0.1 0.2 10 0.7 1.5\n"
      "p 3\n0 0 0\n1 0 0\n0 1 0\n"
      "p 4 0 0 0 2 0 0 2 2 0 0 2 0\n"
      "p 6\n0 0 0\n3 0 0\n3 3 0\n2 3 0\n2 1 0\n0 1 0\n"  // concave L
      "pp 3\n0 0 1 0 0 1\n1 0 1 0 0 2\n0 1 1 0 0 1\n"
      "f 1 0.5 0 0.8 0.2 30 0 0\n");  // repeats the first: same material
  EXPECT_EQ(s.background, tracer::Color(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(s.camera.position, Vec3(2, 0, 0));
  EXPECT_EQ(s.camera.up, Vec3(1, 0, 1));
  EXPECT_FLOAT_EQ(s.camera.vfov_deg, 45.0f);
  EXPECT_FLOAT_EQ(s.camera.hither, 0.01f);
  EXPECT_TRUE(s.camera.left_handed);  // SPD worlds are left-handed (SPD README)
  EXPECT_EQ(s.camera.width, 32);
  EXPECT_EQ(s.camera.height, 16);

  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].color, tracer::Color(1.0f));
  EXPECT_EQ(s.lights[1].color, tracer::Color(0.5f, 0.25f, 1.0f));
  EXPECT_GT(s.lights[0].power_w, 0.0f);

  ASSERT_EQ(s.materials.size(), 2u);
  const tracer::Material& m0 = s.materials[0];
  EXPECT_EQ(m0.type, tracer::MaterialType::Nff);
  EXPECT_EQ(m0.albedo, tracer::Color(1.0f, 0.5f, 0.0f));
  EXPECT_FLOAT_EQ(m0.kd, 0.8f);
  EXPECT_FLOAT_EQ(m0.ks, 0.2f);
  EXPECT_FLOAT_EQ(m0.shininess, 30.0f);
  EXPECT_FLOAT_EQ(m0.transmittance, 0.0f);
  EXPECT_FLOAT_EQ(m0.ior, 1.0f);  // 0 on an opaque material reads as 1
  EXPECT_FLOAT_EQ(s.materials[1].transmittance, 0.7f);
  EXPECT_FLOAT_EQ(s.materials[1].ior, 1.5f);

  const tracer::Geometry& g = s.geometry;
  ASSERT_EQ(g.spheres.size(), 2u);
  EXPECT_FLOAT_EQ(g.spheres[1].radius, -2.0f);  // inside visible
  ASSERT_EQ(g.cones.size(), 2u);
  EXPECT_FLOAT_EQ(g.cones[0].base_radius, 0.2f);
  EXPECT_FLOAT_EQ(g.cones[0].apex_radius, 0.1f);
  EXPECT_FLOAT_EQ(g.cones[1].height, 2.0f);
  EXPECT_EQ(g.cones[1].axis, Vec3(0, 0, 1));
  ASSERT_EQ(g.triangles.size(), 2u);  // p 3 and pp 3
  EXPECT_EQ(g.triangles[0].normals, -1);
  EXPECT_EQ(g.triangles[0].material, 1u);
  ASSERT_EQ(g.triangles[1].normals, 0);
  ASSERT_EQ(g.vertex_normals.size(), 3u);
  EXPECT_EQ(g.vertex_normals[1], Vec3(0, 0, 1));  // normalised
  ASSERT_EQ(g.polygons.size(), 2u);
  EXPECT_EQ(g.polygons[0].vertex_count, 4u);
  EXPECT_EQ(g.polygons[1].vertex_count, 6u);
  EXPECT_EQ(g.polygons[1].first_vertex, 4u);
  EXPECT_EQ(g.polygons[1].normal, Vec3(0, 0, 1));
  EXPECT_EQ(g.polygon_vertices.size(), 10u);
  EXPECT_EQ(g.bounded_count(), 2u + 2u + 2u + 2u);
}

struct BrokenCase {
  std::string text;
  std::string error;
};

TEST(Nff, BrokenFilesGiveExactErrors) {
  const std::vector<BrokenCase> cases = {
      {kView + "s 1 2 3\n", "t.nff:8: expected 4 numbers after 's', got 3"},
      {kView + "s 1 2 3\ns 0 0 0 1\n", "t.nff:8: expected 4 numbers after 's', got 3"},
      {kView + "s 1 2 x 4\n", "t.nff:8: expected 4 numbers after 's', got 2"},
      {kView + "p 4\n0 0 0\n1 0 0\n1 1 0\n",
       "t.nff:8: expected 12 numbers after 'p' (4 vertices), got 9"},
      {kView + "pp 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n",
       "t.nff:8: expected 18 numbers after 'pp' (3 vertices with normals), got 12"},
      {kView + "p 2\n0 0 0\n1 0 0\n", "t.nff:8: 'p' needs 3 to 1000000 vertices, got '2'"},
      {kView + "p 99999999999\n0 0 0\n", "t.nff:8: 'p' needs 3 to 1000000 vertices, got '99999999999'"},
      {kView + "p\nx\n", "t.nff:9: expected a vertex count after 'p', got 'x'"},
      {kView + "p 3.5\n", "t.nff:8: expected a vertex count after 'p', got '3.5'"},
      {kView + "p", "t.nff:8: expected a vertex count after 'p'"},
      {kView + "q 1 2 3\n", "t.nff:8: unknown entity 'q'"},
      {kView + "f 1 1 1 0.5 0.5 10 0.5 0\n",
       "t.nff:8: 'f' with T > 0 needs an index of refraction > 0"},
      {kView + "f 1 1 1 -0.5 0.5 10 0 0\n", "t.nff:8: 'f' values must be >= 0, got -0.500000"},
      {kView + "f 1 1 1 0.5\n", "t.nff:8: expected 8 numbers after 'f', got 4"},
      {kView + "c 0 0 0 1 0 0 0 1\n", "t.nff:8: 'c' base and apex are the same point"},
      // 10^38 apart: the distance overflows float, and the axis would be zero (found by fuzzing).
      {kView + "c 1 0 1e38 -0.5 1 1 0 -1\n", "t.nff:8: 'c' base and apex are too far apart or too close for float (their distance is not a finite non-zero float)"},
      {kView + "c 0 0 0 1 0 0 1 -1\n",
       "t.nff:8: 'c' radii must have the same sign (both < 0: inside visible)"},
      {kView + "c 0 0 0 0 0 0 1 0\n", "t.nff:8: 'c' radii are both zero"},
      {kView + "c 0 0 0 1\n0 0\n", "t.nff:8: expected 8 numbers after 'c', got 6"},
      {kView + "l 1 2 3 4 5\n", "t.nff:8: expected 3 or 6 numbers after 'l', got 5"},
      {kView + "l 1 2\n", "t.nff:8: expected 3 numbers after 'l', got 2"},
      {kView + "s 0 0 0 nan\n", "t.nff:8: number 'nan' is not finite"},
      {kView + "s 0 0 0\n1e39\n", "t.nff:9: number '1e39' is beyond float range (magnitude at most 3.4e38)"},
      {kView + "s 1e999 0 0 0.5\n", "t.nff:8: number '1e999' is beyond float range (magnitude at most 3.4e38)"},
      {kView + "s 0 0 0 inf\n", "t.nff:8: number 'inf' is not finite"},
      {kView + "p 1e999\n", "t.nff:8: 'p' needs 3 to 1000000 vertices, got '1e999'"},
      {kView + "p 4\n0 0 0\n1 0 0\n2 0 0\n3 0 0\n",
       "t.nff:8: 'p' polygon is degenerate: its vertices do not span a plane"},
      {kView + "b 0 -0.5 0\n", "t.nff:8: 'b' colour values must be >= 0, got -0.500000"},
      {kView + "l 1 2 3 1 -1 1\n", "t.nff:8: 'l' colour values must be >= 0, got -1.000000"},
      {kView + "l 3e38 0 0\n", "t.nff:8: 'l' light is too far from the look-at point (its power overflows float)"},
      {kView + "s 0 0 0 0\n", "t.nff:8: 's' radius must be non-zero"},
      {kView + "pp 3\n0 0 0 0 0 0\n1 0 0 0 0 1\n0 1 0 0 0 1\n",
       "t.nff:8: 'pp' vertex 1 has a zero normal"},
      {kView + "v\n", "t.nff:8: second 'v' viewpoint"},
      {"b 0 0 0\ns 0 0 0 1\n", "t.nff:2: no 'v' viewpoint in the file"},
      {"", "t.nff:1: no 'v' viewpoint in the file"},
      {"v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nhither 1\nresolution 64 64\n",
       "t.nff:1: 'v' is missing 'angle'"},
      {"v\nfrom 0 0 5\nat 0 0 0\nup 0 0 1\nangle 45\nhither 1\nresolution 64 64\n",
       "t.nff:1: 'v' has an 'up' parallel to the view direction (or zero)"},
      {"v\nfrom 0 0 5\nat 0 0 5\nup 0 1 0\nangle 45\nhither 1\nresolution 64 64\n",
       "t.nff:1: 'v' has 'from' equal to 'at'"},
      {"v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 180\nhither 1\nresolution 64 64\n",
       "t.nff:1: 'v' angle must be in (0, 180) degrees, got 180.000000"},
      {"v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 0 64\n",
       "t.nff:1: 'v' resolution must be two integers in [1, 16384]"},
      {"v\nfrom 1 2\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 64 64\n",
       "t.nff:2: expected 3 numbers after 'from', got 2"},
      {"v\nfrom 0 0 5\nfrom 0 0 5\n", "t.nff:3: 'v' gives 'from' twice"},
      {kView + "\x01\x02garbage\n", "t.nff:8: unknown entity '??garbage'"},
  };
  for (const BrokenCase& c : cases) EXPECT_EQ(nff_error(c.text), c.error) << c.text;
}

#ifdef ACCELBENCH_SPD_DIR
const std::filesystem::path kSpdDir = ACCELBENCH_SPD_DIR;
#else
const std::filesystem::path kSpdDir;
#endif

using test_files::read;

struct SpdCounts {
  const char* file;
  std::size_t spheres, triangles, cones, polygons, lights;
};

class SpdFile : public ::testing::TestWithParam<SpdCounts> {};

TEST_P(SpdFile, ParsesWithTheDocumentedPrimitiveCounts) {
  const SpdCounts& want = GetParam();
  const auto path = kSpdDir / want.file;
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "SPD scenes not found at " << path;
  const Scene s = load_nff(path.string());
  EXPECT_EQ(s.geometry.spheres.size(), want.spheres);
  EXPECT_EQ(s.geometry.triangles.size(), want.triangles);
  EXPECT_EQ(s.geometry.cones.size(), want.cones);
  EXPECT_EQ(s.geometry.polygons.size(), want.polygons);
  EXPECT_EQ(s.lights.size(), want.lights);
  EXPECT_EQ(s.camera.width, 512);
  EXPECT_EQ(s.camera.height, 512);
  EXPECT_FLOAT_EQ(s.camera.vfov_deg, 45.0f);
  EXPECT_EQ(s.background, tracer::Color(0.078f, 0.361f, 0.753f));
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, SpdFile,
    ::testing::Values(SpdCounts{"balls_sf2.nff", 91, 0, 0, 1, 3},
                      SpdCounts{"balls_sf4.nff", 7381, 0, 0, 1, 3},
                      SpdCounts{"gears_sf4.nff", 0, 0, 0, 9345, 5},
                      SpdCounts{"mount_sf6.nff", 4, 8192, 0, 0, 1},
                      SpdCounts{"rings_sf7.nff", 4200, 0, 4200, 1, 3},
                      SpdCounts{"teapot_sf12.nff", 0, 9120, 0, 144, 2},
                      SpdCounts{"tetra_sf6.nff", 0, 4096, 0, 0, 1},
                      SpdCounts{"tree_sf11.nff", 4095, 0, 4095, 1, 7}),
    [](const ::testing::TestParamInfo<SpdCounts>& param_info) {
      std::string n = param_info.param.file;
      return n.substr(0, n.find('.'));
    });

// Every prefix of a real file either parses or raises one SceneError: no crash, no hang.
TEST(Nff, TruncatedAndGarbledFilesNeverCrash) {
  const auto path = kSpdDir / "balls_sf2.nff";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "SPD scenes not found at " << path;
  const std::string text = read(path);
  int parsed = 0, rejected = 0;
  for (std::size_t len = 0; len <= text.size(); len += 7) {
    const std::string err = nff_error(text.substr(0, len));
    (err.empty() ? parsed : rejected)++;
    if (!err.empty()) {
      EXPECT_EQ(err.find('\n'), std::string::npos);
    }
  }
  EXPECT_GT(parsed, 0);
  EXPECT_GT(rejected, 0);
  std::mt19937 rng(11);
  for (int i = 0; i < 200; ++i) {
    std::string noisy = text;
    for (int k = 0; k < 5; ++k)
      noisy[rng() % noisy.size()] = char(rng() % 256);
    const std::string err = nff_error(noisy);
    if (!err.empty()) {
      EXPECT_EQ(err.rfind("t.nff:", 0), 0u) << err;
    }
  }
}

TEST(Nff, MissingFileIsOneLine) {
  try {
    load_nff("/nonexistent/dir/x.nff");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/dir/x.nff: cannot open: No such file or directory");
  }
}

}  // namespace
