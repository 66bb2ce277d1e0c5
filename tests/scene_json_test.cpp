// Scene JSON: a table of bad inputs with their exact one-line messages, and the round trip.

#include "tracer/scene_io.h"
#include "tracer/scene_json.h"

#include "scenes_gen/generators.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace {

using nlohmann::json;

json valid_scene() {
  return json::parse(R"({
    "camera": {"position": [0, 1, 5], "look_at": [0, 0, 0], "up": [0, 1, 0], "vfov": 45,
               "resolution": [64, 48], "samples_per_pixel": 1},
    "background": [0.1, 0.1, 0.2],
    "lights": [{"position": [5, 5, 5], "power": 1000, "color": [1, 1, 1]}],
    "materials": [
      {"name": "matte", "type": "diffuse", "albedo": [0.8, 0.8, 0.8], "specular": 0.2, "shininess": 20},
      {"name": "chrome", "type": "mirror", "reflectance": 0.9},
      {"name": "glass", "type": "dielectric", "ior": 1.5, "absorption": [0, 0.1, 0.2]}],
    "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "glass"},
                {"center": [2, 0, 0], "radius": 0.5, "material": "chrome"}],
    "planes": [{"normal": [0, 2, 0], "offset": -1, "material": "matte"}],
    "boxes": [{"min": [-3, -1, -3], "max": [-2, 0, -2], "material": "matte"}],
    "triangles": [{"vertices": [[0, 0, -4], [1, 0, -4], [0, 1, -4]], "material": "matte"}],
    "meshes": [{"vertices": [[0, 0, -5], [1, 0, -5], [1, 1, -5], [0, 1, -5]],
                "indices": [[0, 1, 2], [0, 2, 3]],
                "normals": [[0, 0, 1], [0, 0, 1], [0, 0.1, 1], [0, 0, 1]], "material": "matte"}],
    "render": {"max_depth": 6, "min_weight": 0.01}
  })");
}

std::string scene_json_error(const json& doc) {
  try {
    tracer::scene_from_json(doc);
  } catch (const tracer::SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string error_of_text(const std::string& text) {
  try {
    tracer::parse_scene_json(text);
  } catch (const tracer::SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

struct BadCase {
  const char* pointer;  ///< Where to put the value (JSON pointer).
  json value;           ///< The bad value; a null with `remove` set deletes the key instead.
  const char* message;  ///< The exact expected error.
  bool remove = false;
};

TEST(SceneJson, ValidSceneLoads) {
  const tracer::Scene s = tracer::scene_from_json(valid_scene());
  EXPECT_EQ(s.geometry.spheres.size(), 2u);
  EXPECT_EQ(s.geometry.triangles.size(), 3u);  // one triangle + a two-triangle mesh
  EXPECT_EQ(s.geometry.vertex_normals.size(), 6u);
  EXPECT_EQ(s.geometry.bounded_count(), 6u);
  EXPECT_EQ(s.geometry.planes[0].normal, tracer::Vec3(0.0f, 1.0f, 0.0f));  // normalised
  EXPECT_EQ(s.materials[1].reflectance, tracer::Color(0.9f));              // grey shorthand
  EXPECT_EQ(s.geometry.spheres[1].material, 1u);
  EXPECT_EQ(s.camera.width, 64);
  EXPECT_EQ(s.render.max_depth, 6);
}

TEST(SceneJson, EveryBadValueNamesItsPath) {
  const std::vector<BadCase> cases = {
      {"/spheres/1/radius", -1, "/spheres/1/radius: must be > 0, got -1"},
      {"/spheres/1/radius", 0.0, "/spheres/1/radius: must be > 0, got 0.0"},
      {"/spheres/1/radius", "big", "/spheres/1/radius: must be a number, got \"big\""},
      {"/spheres/1/radius", true, "/spheres/1/radius: must be a number, got true"},
      {"/spheres/1/radius", 1e300,
       "/spheres/1/radius: is beyond float range (magnitude at most 3.4e38), got 1e+300"},
      {"/spheres/1/radius", 3.5e38,
       "/spheres/1/radius: is beyond float range (magnitude at most 3.4e38), got 3.5e+38"},
      {"/spheres/1/radius", json(), "/spheres/1: missing required key 'radius'", true},
      {"/spheres/1/center", json::array({1, 2}),
       "/spheres/1/center: must be an array of 3 numbers, got [1,2]"},
      {"/spheres/1/center/2", "z", "/spheres/1/center/2: must be a number, got \"z\""},
      {"/spheres/1/material", "glas",
       "/spheres/1/material: unknown material \"glas\" (known: matte, chrome, glass)"},
      {"/spheres/1/radus", 1, "/spheres/1/radus: unknown key in sphere; did you mean 'radius'?"},
      {"/spheres/0", 5, "/spheres/0: must be an object, got 5"},
      {"/spheres", json::object(), "/spheres: must be an array, got {}"},
      {"/sphere", json::array(), "/sphere: unknown key in scene; did you mean 'spheres'?"},
      {"/foo", 1,
       "/foo: unknown key in scene (expected one of camera, background, lights, materials, "
       "spheres, "
       "planes, boxes, triangles, meshes, cones, polygons, render, integrator)"},
      {"/materials/2/ior", 0, "/materials/2/ior: must be > 0, got 0"},
      {"/materials/2/ior", -1.5, "/materials/2/ior: must be > 0, got -1.5"},
      {"/materials/2/albedo", 0.5,
       "/materials/2/albedo: unknown key in dielectric material (expected one of name, "
       "type, ior, absorption)"},
      {"/materials/2/type", "metal",
       "/materials/2/type: unknown material type \"metal\" (expected diffuse, mirror, "
       "dielectric or nff)"},
      {"/materials/2/name", "matte", "/materials/2/name: duplicate material name \"matte\""},
      {"/materials/0/albedo/1", 1.5, "/materials/0/albedo/1: must be in [0, 1], got 1.5"},
      {"/materials/0/specular", 2, "/materials/0/specular: must be in [0, 1], got 2"},
      {"/materials/1/reflectance", -0.1, "/materials/1/reflectance: must be in [0, 1], got -0.1"},
      {"/camera/resolution", json::array({0, 48}),
       "/camera/resolution/0: must be in [1, 65536], got 0"},
      {"/camera/resolution", json::array({64, -48}),
       "/camera/resolution/1: must be in [1, 65536], got -48"},
      {"/camera/resolution", json::array({64.5, 48}),
       "/camera/resolution/0: must be an integer, got 64.5"},
      {"/camera/resolution", "640x480",
       "/camera/resolution: must be [width, height] in pixels, got \"640x480\""},
      {"/camera/vfov", 180, "/camera/vfov: must be in (0, 180) degrees, got 180"},
      {"/camera/up", json::array({0, 2, 10}),
       "/camera/up: must not be parallel to the view direction"},
      {"/camera/look_at", json::array({0, 1, 5}), "/camera/look_at: must differ from position"},
      {"/camera/samples_per_pixel", 0, "/camera/samples_per_pixel: must be in [1, 65536], got 0"},
      {"/lights/0/power", -5, "/lights/0/power: must be >= 0 watts, got -5"},
      {"/lights/0/color/0", -1, "/lights/0/color/0: must be >= 0, got -1"},
      {"/planes/0/normal", json::array({0, 0, 0}),
       "/planes/0/normal: must be a non-zero vector, got [0,0,0]"},
      {"/boxes/0/max/1", -1, "/boxes/0/max/1: must be > min/1 (-1), got -1"},
      {"/triangles/0/vertices", json::array({json::array({0, 0, 0})}),
       "/triangles/0/vertices: must be an array of 3 points, got [[0,0,0]]"},
      {"/meshes/0/indices/1/2", 4,
       "/meshes/0/indices/1/2: vertex index 4 is out of range (the mesh has 4 vertices)"},
      {"/meshes/0/indices/1/2", -1, "/meshes/0/indices/1/2: must be >= 0, got -1"},
      {"/meshes/0/normals/3", json::array({0, 0, 0}),
       "/meshes/0/normals/3: must be a non-zero vector, got [0,0,0]"},
      {"/render/max_depth", 0, "/render/max_depth: must be in [1, 1000], got 0"},
      {"/render/min_weight", 2, "/render/min_weight: must be in [0.0, 1.0], got 2"},
      {"/render/max_depth", 2.5, "/render/max_depth: must be an integer, got 2.5"},
  };
  for (const BadCase& c : cases) {
    json doc = valid_scene();
    const json::json_pointer ptr(c.pointer);
    if (c.remove)
      doc[ptr.parent_pointer()].erase(ptr.back());
    else
      doc[ptr] = c.value;
    EXPECT_EQ(scene_json_error(doc), c.message) << "at " << c.pointer;
  }
}

// The render object is a knob table: the scene reader, the writer and the docs table come from it.
TEST(SceneJson, TheRenderObjectIsItsKnobTable) {
  json doc = valid_scene();
  doc["render"] = {{"maxdepth", 3}};
  EXPECT_EQ(scene_json_error(doc), "/render/maxdepth: unknown key in render settings; did you mean 'max_depth'?");
  const tracer::Scene s = tracer::scene_from_json(valid_scene());
  EXPECT_EQ(tracer::scene_to_json(s)["render"], tracer::RenderSettings::knobs().to_json(s.render));
  std::ifstream in(ACCELBENCH_SOURCE_DIR "/docs/scene-format.md");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find(tracer::RenderSettings::knobs().markdown()), std::string::npos)
      << "docs/scene-format.md: put this table under `render`:\n" << tracer::RenderSettings::knobs().markdown();
}

TEST(SceneJson, NaNsAreRejectedWhereTheyStand) {
  json doc = valid_scene();
  doc["spheres"][1]["radius"] = std::nan("");
  EXPECT_EQ(scene_json_error(doc),
            "/spheres/1/radius: must be a finite number, got null");  // json dumps NaN as null
  // In text, a NaN literal (as Python's json module writes) is not JSON, yet is found in place.
  std::string text = valid_scene().dump();
  text.replace(text.find("\"radius\":0.5"), 12, "\"radius\":NaN");
  EXPECT_EQ(error_of_text(text), "/spheres/1/radius: must be a finite number, got NaN");
  EXPECT_EQ(error_of_text(R"({"camera": {"vfov": -Infinity}})"),
            "/camera/vfov: must be a finite number, got -Infinity");
}

TEST(SceneJson, SyntaxErrorsNameTheirPlace) {
  EXPECT_EQ(error_of_text(R"({"spheres": [{"center": [0, 0, 0], "radius": 1,}]})"),
            "/spheres/0/radius: invalid JSON: parse error at line 1, column 48: syntax error while "
            "parsing "
            "object key - unexpected '}'; expected string literal");
  EXPECT_EQ(error_of_text("[1, 2"),
            "/2: invalid JSON: parse error at line 1, column 6: syntax error while "
            "parsing array - unexpected end of input; expected ']'");
  EXPECT_EQ(error_of_text("[1, 2]"), "(root): must be an object, got [1,2]");
}

TEST(SceneJson, RoundTripIsExact) {
  const tracer::Scene a = tracer::scene_from_json(valid_scene());
  const json saved = tracer::scene_to_json(a);
  const tracer::Scene b = tracer::parse_scene_json(saved.dump());
  const json saved_again = tracer::scene_to_json(b);
  EXPECT_EQ(saved, saved_again);
  EXPECT_EQ(b.geometry.vertex_normals, a.geometry.vertex_normals);
  ASSERT_EQ(b.geometry.triangles.size(), a.geometry.triangles.size());
  EXPECT_EQ(b.geometry.triangles[2].p2, a.geometry.triangles[2].p2);
  EXPECT_EQ(b.geometry.spheres[1].center, a.geometry.spheres[1].center);
  EXPECT_EQ(b.materials[2].absorption, a.materials[2].absorption);
  // Shortest exact floats: 0.1 stays 0.1 in the file.
  EXPECT_EQ(saved["background"][0].dump(), "0.1");
}

// NFF's negative radius (only the inside visible) survives conversion to JSON and back, while a
// negative "radius" in JSON stays an error.
TEST(SceneJson, InsideVisibleSphereRoundTrips) {
  tracer::Scene a = tracer::scene_from_json(valid_scene());
  a.geometry.spheres[0].radius = -2.5f;
  const json saved = tracer::scene_to_json(a);
  EXPECT_EQ(saved["spheres"][0]["radius"].dump(), "2.5");
  EXPECT_EQ(saved["spheres"][0]["inside_visible"], true);
  EXPECT_FALSE(saved["spheres"][1].contains("inside_visible"));
  const tracer::Scene b = tracer::parse_scene_json(saved.dump());
  EXPECT_EQ(b.geometry.spheres[0].radius, -2.5f);
  EXPECT_EQ(b.geometry.spheres[1].radius, a.geometry.spheres[1].radius);
}

// The scene may choose its integrator and that integrator's knobs: the tracer stores them (bench/
// knows the integrators and checks both), and they round-trip.
TEST(SceneJson, IntegratorChoiceIsStoredAndRoundTrips) {
  json doc = valid_scene();
  doc["integrator"] = {{"name", "photon"}, {"k", 20}, {"filter", "box"}};
  const tracer::Scene a = tracer::scene_from_json(doc);
  EXPECT_EQ(a.integrator.name, "photon");
  EXPECT_EQ(a.integrator.knobs, (json{{"k", 20}, {"filter", "box"}}));
  const tracer::Scene b = tracer::parse_scene_json(tracer::scene_to_json(a).dump());
  EXPECT_EQ(b.integrator.name, "photon");
  EXPECT_EQ(b.integrator.knobs, a.integrator.knobs);
  doc["integrator"] = "spd";
  EXPECT_EQ(tracer::scene_from_json(doc).integrator.name, "spd");
  EXPECT_TRUE(tracer::scene_from_json(valid_scene()).integrator.name.empty());
  EXPECT_FALSE(tracer::scene_to_json(tracer::scene_from_json(valid_scene())).contains("integrator"));
  for (const json& bad : {json(3), json{{"k", 20}}, json(""), json{{"name", ""}}}) {
    doc["integrator"] = bad;
    EXPECT_EQ(scene_json_error(doc).rfind("/integrator: ", 0), 0u) << bad.dump() << ": " << scene_json_error(doc);
  }
}

TEST(SceneJson, GeneratedScenesRoundTripThroughFiles) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "accelbench_scene_json_test.json").string();
  for (const char* name : {"refraction", "five", "spheres8000", "ring", "cornell", "furnace"}) {
    const tracer::Scene a = scenes_gen::generate(name, {});
    tracer::save_scene_file(a, path);
    const tracer::Scene b = tracer::load_scene_file(path);
    EXPECT_EQ(tracer::scene_to_json(a), tracer::scene_to_json(b)) << name;
    EXPECT_EQ(a.geometry.bounded_count(), b.geometry.bounded_count());
  }
  std::remove(path.c_str());
}

// The random generators' scenes are pinned bit for bit ("same options, same bits" on every
// platform and compiler): an FNV-1a hash of every sphere's centre, radius and material. The
// values are those of the scenes every published figure used. A draw left to the compiler's
// order of evaluating arguments (spheres8000 once drew Vec3(u(), u(), u()): clang drew another
// scene than gcc) or a change to Rng moves them.
std::uint64_t sphere_bits_hash(const tracer::Scene& scene) {
  std::uint64_t h = 1469598103934665603ull;
  const auto mix = [&h](std::uint32_t word) { h = (h ^ word) * 1099511628211ull; };
  for (const tracer::Sphere& s : scene.geometry.spheres) {
    for (int k = 0; k < 3; ++k) mix(std::bit_cast<std::uint32_t>(s.center[k]));
    mix(std::bit_cast<std::uint32_t>(s.radius));
    mix(s.material);
  }
  return h;
}

TEST(Generators, RandomScenesArePinnedBitForBit) {
  const tracer::Scene s8000 = scenes_gen::generate("spheres8000", {});
  ASSERT_EQ(s8000.geometry.spheres.size(), 8000u);
  EXPECT_EQ(sphere_bits_hash(s8000), 0x66bf14c096a2eda4ull);
  scenes_gen::GenOptions random;
  random.seed = 7;
  random.count = 1000;
  EXPECT_EQ(sphere_bits_hash(scenes_gen::generate("random", random)), 0xdb172f18ccff374dull);
}

TEST(SceneIo, FileErrorsStartWithThePath) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "accelbench_bad_scene.json").string();
  json doc = valid_scene();
  doc["spheres"][1]["radius"] = -1;
  std::ofstream(path) << doc.dump();
  try {
    tracer::load_scene_file(path);
    FAIL() << "no error";
  } catch (const tracer::SceneError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": /spheres/1/radius: must be > 0, got -1");
  }
  std::remove(path.c_str());
  EXPECT_THROW(tracer::load_scene_file("/nonexistent/scene.json"), tracer::SceneError);
  EXPECT_THROW(tracer::load_scene_file("scene.obj"), tracer::SceneError);
}

}  // namespace
