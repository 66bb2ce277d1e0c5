#include "tracer/nff.h"
#include "tracer/scene_io.h"
#include "tracer/render.h"

#include "structure_configs.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>

namespace {

using tracer::RayCounts;
using tracer::RenderResult;
using tracer::Scene;

#ifdef ACCELBENCH_SPD_DIR
const std::filesystem::path kSpdDir = ACCELBENCH_SPD_DIR;
#else
const std::filesystem::path kSpdDir;
#endif

Scene parse(const std::string& text) {
  std::istringstream in(text);
  return tracer::load_nff(in, "t.nff");
}

RenderResult render(const Scene& scene, const test_support::StructureConfig& structure,
                    const tracer::RenderOptions& options = {}) {
  const accel::AnyAccel a = structure.build(scene.geometry.primitive_bounds());
  return tracer::render(scene, a, options, tracer::spd_integrator());
}

// A 4x4 image (25 corner rays) looking down -z from z = 5 at a 2x2 square at z = 0 that fills
// the view (45 degrees see +-2.07 at distance 5).
std::string view(int res = 4) {
  return "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.01\nresolution " +
         std::to_string(res) + " " + std::to_string(res) + "\nb 0.1 0.2 0.3\n";
}
const std::string kFacingSquare = "p 4\n-3 -3 0\n3 -3 0\n3 3 0\n-3 3 0\n";  // normal +z
const std::string kAwaySquare = "p 4\n-3 -3 0\n-3 3 0\n3 3 0\n3 -3 0\n";    // normal -z

TEST(Spd, CornerRaysAndPixelAverages) {
  const Scene s = parse(view() + "l 0 0 10\nf 1 1 1 1 0 1 0 0\n" + kFacingSquare);
  const RenderResult r = render(s, {"naive"});
  EXPECT_EQ(r.image.width(), 4);
  EXPECT_EQ(r.image.height(), 4);
  EXPECT_EQ(r.rays.eye, 25u);
  EXPECT_EQ(r.rays.eye_hits, 25u);
  EXPECT_EQ(r.rays.shadow, 25u);  // one light, facing it
  EXPECT_EQ(r.rays.reflection, 0u);
  EXPECT_EQ(r.rays.refraction, 0u);
}

TEST(Spd, BackgroundSpawnsNothing) {
  const Scene s = parse(view() + "l 0 0 10\n");
  const RenderResult r = render(s, {"naive"});
  EXPECT_EQ(r.rays, (RayCounts{25, 0, 0, 0, 0}));
  for (const auto& p : r.image.pixels()) EXPECT_EQ(p, tracer::Color(0.1f, 0.2f, 0.3f));
}

TEST(Spd, NoShadowRayWhenTheNormalFacesAwayFromTheLight) {
  // Light behind the facing square: no shadow rays.
  EXPECT_EQ(render(parse(view() + "l 0 0 -10\nf 1 1 1 1 0 1 0 0\n" + kFacingSquare), "naive").rays.shadow, 0u);
  // Opaque is one-sided: seen from behind, its normal faces away from a light on our side.
  EXPECT_EQ(render(parse(view() + "l 0 0 10\nf 1 1 1 1 0 1 0 0\n" + kAwaySquare), "naive").rays.shadow, 0u);
  // A transmitter is two-sided: its normal turns to the ray, so it faces the light.
  const RenderResult t =
      render(parse(view() + "l 0 0 10\nf 1 1 1 1 0 1 0.5 1.0\n" + kAwaySquare), "naive");
  EXPECT_EQ(t.rays.shadow, 25u);
  EXPECT_EQ(t.rays.reflection, 25u);  // transmitters always reflect, even with Ks = 0
  EXPECT_EQ(t.rays.refraction, 25u);  // ior 1: straight through to the background
}

TEST(Spd, TreeDepthIsFive) {
  // Inside a mirror sphere whose inside is visible (negative radius), with the light inside:
  // every ray hits, so each eye ray makes 4 reflections (depths 2..5) and 5 shadow rays.
  const Scene s = parse(view() + "l 0 0 1\nf 1 1 1 0.5 0.5 10 0 0\ns 0 0 0 -20\n");
  const RenderResult r = render(s, {"naive"});
  EXPECT_EQ(r.rays, (RayCounts{25, 25, 100, 0, 125}));
}

TEST(Spd, HitherClipsEyeRays) {
  // A small square at z = 4.5 is nearer than hither = 1 and is clipped; the far one is seen.
  const std::string scene =
      "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 4 4\n"
      "f 1 0 0 1 0 1 0 0\np 4\n-3 -3 4.5\n3 -3 4.5\n3 3 4.5\n-3 3 4.5\n"
      "f 0 1 0 1 0 1 0 0\n" + kFacingSquare;
  const RenderResult r = render(parse(scene), "naive");
  EXPECT_EQ(r.rays.eye_hits, 25u);
  EXPECT_GT(r.image.at(1, 1).y, 0.0f);  // green: the far square
  EXPECT_EQ(r.image.at(1, 1).x, 0.0f);
}

TEST(Spd, SameImageAtAnyThreadCount) {
  const auto path = kSpdDir / "balls_sf2.nff";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "SPD scenes not found at " << path;
  const Scene s = tracer::load_nff(path.string());
  tracer::RenderOptions o;
  o.width = o.height = 64;
  o.threads = 1;
  const RenderResult one = render(s, "bvh", o);
  o.threads = 3;
  const RenderResult three = render(s, "bvh", o);
  EXPECT_EQ(one.image.content_hash(), three.image.content_hash());
  EXPECT_EQ(one.rays, three.rays);
}

// `accelbench convert` is load_scene_file (.nff) then save_scene_file (.json): the JSON scene
// must render the same image with the same counts.
TEST(Spd, ConvertedJsonRendersTheSameImage) {
  for (const char* name : {"rings_sf7.nff", "teapot_sf12.nff", "gears_sf4.nff"}) {
    const auto path = kSpdDir / name;
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "SPD scenes not found at " << path;
    const Scene nff = tracer::load_scene_file(path.string());
    const auto json_path = std::filesystem::temp_directory_path() / (std::string("spd_test_") + name + ".json");
    tracer::save_scene_file(nff, json_path.string());
    const Scene json = tracer::load_scene_file(json_path.string());
    std::filesystem::remove(json_path);
    tracer::RenderOptions o;
    o.width = o.height = 48;
    const RenderResult a = render(nff, "bvh", o), b = render(json, "bvh", o);
    EXPECT_EQ(a.image.content_hash(), b.image.content_hash()) << name;
    EXPECT_EQ(a.rays, b.rays) << name;
  }
}

TEST(Spd, BadWindowIsRejected) {
  const Scene s = parse(view() + kFacingSquare);
  tracer::RenderOptions o;
  o.window = {2, 2, 6, 3};
  EXPECT_THROW(render(s, {"naive"}, o), std::invalid_argument);
}

/// Every built structure (Embree at every ISA the CPU has) against naive: same image hash and
/// same ray counts.
void expect_structures_match_naive(const Scene& scene, const tracer::RenderOptions& options) {
  const RenderResult ref = render(scene, {"naive"}, options);
  EXPECT_GT(ref.rays.eye_hits, 0u);
  for (const test_support::StructureConfig& structure : test_support::structures_at_every_isa()) {
    const RenderResult r = render(scene, structure, options);
    EXPECT_EQ(r.image.content_hash(), ref.image.content_hash()) << structure.label();
    EXPECT_EQ(r.rays, ref.rays) << structure.label();
  }
}

TEST(SpdStructures, EqualNaiveOnBallsSf2) {
  const auto path = kSpdDir / "balls_sf2.nff";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "SPD scenes not found at " << path;
  tracer::RenderOptions o;
  o.width = o.height = 192;  // the whole image at reduced size keeps naive quick
  expect_structures_match_naive(tracer::load_nff(path.string()), o);
}

class SpdWindow : public ::testing::TestWithParam<const char*> {};

// A 24x24 window around the centre of the full 512x512 image of each scene.
TEST_P(SpdWindow, EveryStructureEqualsNaive) {
  const auto path = kSpdDir / GetParam();
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "SPD scenes not found at " << path;
  const Scene s = tracer::load_nff(path.string());
  tracer::RenderOptions o;
  o.window = {244, 244, 268, 268};
  expect_structures_match_naive(s, o);
}

INSTANTIATE_TEST_SUITE_P(Scenes, SpdWindow,
                         ::testing::Values("balls_sf4.nff", "gears_sf4.nff", "mount_sf6.nff",
                                           "rings_sf7.nff", "teapot_sf12.nff", "tetra_sf6.nff",
                                           "tree_sf11.nff"),
                         [](const ::testing::TestParamInfo<const char*>& param_info) {
                           const std::string n = param_info.param;
                           return n.substr(0, n.find('.'));
                         });

}  // namespace
