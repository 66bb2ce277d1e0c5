// Model files (tracer/mesh_file.*, ply_header.*, ply_reader.*) and meshes in scenes: the shared
// standard models load with the counts their README gives, our PLY reader agrees with assimp on
// faces, every kind of bad file is one line naming the file, and a scene refers to its model
// files through save and load.

#include "scenes_gen/mesh_scenes.h"
#include "tracer/mesh_file.h"
#include "tracer/scene_error.h"
#include "tracer/scene_io.h"
#include "tracer/scene_json.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace {

namespace fs = std::filesystem;
using tracer::MeshData;
using tracer::MeshFormat;

const fs::path kMeshes = ACCELBENCH_MESHES_DIR;

class TempDir {
 public:
  TempDir() : path_(fs::temp_directory_path() / ("accelbench_mesh_" + std::to_string(::getpid()))) {
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

void write(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary);
  out << bytes;
}

/// The one-line message a bad file gets.
std::string mesh_error(const std::string& bytes, MeshFormat format, const std::string& name) {
  try {
    tracer::parse_mesh(bytes, format, name);
  } catch (const tracer::SceneError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    return m;
  }
  return "loaded";
}

TEST(MeshFile, SharedModelsLoadWithTheirReadmeCounts) {
  if (!fs::exists(kMeshes)) GTEST_SKIP() << kMeshes << " is absent: the shared standard models are not tested";
  struct Expect {
    const char* file;
    std::uint64_t vertices, triangles;
  };
  // Triangles: the README's faces, quads and polygons split (beast: 32,228 quads, 124
  // triangles, 10 pentagons, 2 hexagons), igea's strips unpacked.
  const Expect models[] = {{"stanford-bunny.obj", 35947, 69451}, {"ogre.obj", 62194, 124008},
                           {"nefertiti.obj", 49971, 99938},      {"beast.obj", 32311, 64618},
                           {"igea.ply", 134345, 268686},         {"teapot.obj", 3644, 6320},
                           {"spot.obj", 2930, 5856},             {"fandisk.obj", 6475, 12946}};
  for (const Expect& e : models) {
    const MeshData m = tracer::load_mesh_file((kMeshes / e.file).string());
    EXPECT_EQ(m.stats.vertices, e.vertices) << e.file;
    EXPECT_EQ(m.stats.triangles + m.stats.degenerate, e.triangles) << e.file;
    EXPECT_EQ(m.stats.triangles, m.triangles.size()) << e.file;
    EXPECT_EQ(m.stats.file_bytes, fs::file_size(kMeshes / e.file)) << e.file;
  }
}

/// `mesh` as a PLY file with faces, ASCII or binary little-endian.
std::string ply_of(const MeshData& mesh, bool binary) {
  std::ostringstream o;
  o << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\nelement vertex "
    << mesh.vertices.size() << "\nproperty float x\nproperty float y\nproperty float z\nelement face "
    << mesh.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  if (!binary) o.precision(9);
  for (const accel::Vec3& p : mesh.vertices) {
    if (binary) o.write(reinterpret_cast<const char*>(&p), sizeof p);
    else o << p.x << ' ' << p.y << ' ' << p.z << '\n';
  }
  for (const auto& t : mesh.triangles) {
    if (binary) {
      const char three = 3;
      o.write(&three, 1);
      for (const std::uint32_t i : t) {
        const std::int32_t v = std::int32_t(i);
        o.write(reinterpret_cast<const char*>(&v), sizeof v);
      }
    } else {
      o << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
    }
  }
  return o.str();
}

TEST(MeshFile, OurPlyReaderAgreesWithAssimpOnFaces) {
  if (!fs::exists(kMeshes)) GTEST_SKIP() << kMeshes << " is absent";
  const MeshData bunny = tracer::load_mesh_file((kMeshes / "stanford-bunny.obj").string());
  for (const bool binary : {false, true}) {
    const std::string bytes = ply_of(bunny, binary);
    const MeshData ours = tracer::parse_mesh(bytes, MeshFormat::Ply, "bunny.ply");
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(), aiProcess_Triangulate, "ply");
    ASSERT_TRUE(scene && scene->mNumMeshes == 1) << importer.GetErrorString();
    const aiMesh* theirs = scene->mMeshes[0];
    ASSERT_EQ(ours.triangles.size(), theirs->mNumFaces) << (binary ? "binary" : "ascii");
    // Binary: the same bits. ASCII: assimp's own number parser (fast_atoreal) is not correctly
    // rounded and misses the nearest float by an ulp on some coordinates, where from_chars, ours,
    // is exact (the comparison with the OBJ below).
    std::size_t differ = 0, apart = 0;
    for (std::size_t f = 0; f < ours.triangles.size(); ++f)
      for (int k = 0; k < 3; ++k) {
        const aiVector3D& q = theirs->mVertices[theirs->mFaces[f].mIndices[k]];
        const accel::Vec3& p = ours.vertices[ours.triangles[f][std::size_t(k)]];
        differ += p != accel::Vec3(q.x, q.y, q.z);
        apart += glm::length(p - accel::Vec3(q.x, q.y, q.z)) > 1e-6f * (1.0f + glm::length(p));
      }
    EXPECT_EQ(binary ? differ : apart, 0u) << (binary ? "binary" : "ascii");
    // And both agree with the OBJ they were written from.
    EXPECT_EQ(ours.vertices, bunny.vertices);
    EXPECT_EQ(ours.triangles, bunny.triangles);
  }
}

TEST(MeshFile, TriangleStripsUnpackWithTheirWinding) {
  const std::string strip =
      "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
      "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 2 0\n6 0 1 2 3 -1 4\n";
  const MeshData m = tracer::parse_mesh(strip, MeshFormat::Ply, "strip.ply");
  // 0 1 2 3: (0 1 2), then (2 1 3) flipped back to counter-clockwise; -1 restarts; "4" alone makes none.
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(m.triangles[1], (std::array<std::uint32_t, 3>{2, 1, 3}));
}

TEST(MeshFile, PolygonsSplitAndDegenerateTrianglesAreDropped) {
  const MeshData m = tracer::parse_mesh(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nf 1 2 3 4\nf 1 2 5\nf 1 1 3\n", MeshFormat::Obj, "m.obj");
  EXPECT_EQ(m.triangles.size(), 2u);  // the quad; (1 2 5) is collinear, (1 1 3) repeats a vertex
  EXPECT_EQ(m.stats.degenerate, 2u);
}

TEST(MeshFile, BadFilesGetOneLineNamingTheFile) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::string ply_head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  struct Case {
    const char* what;
    std::string bytes;
    MeshFormat format;
    std::string message;
  };
  const Case cases[] = {
      {"empty", "", MeshFormat::Obj, "m.obj: is empty"},
      {"an index past the end", tri + "f 1 2 4\n", MeshFormat::Obj,
       "m.obj: face 0: vertex index 3 is out of range (the mesh has 3 vertices, indexed from 0)"},
      {"a relative index before the first vertex", tri + "f -1 -2 -4\n", MeshFormat::Obj,
       "m.obj: face 0: vertex index -1 is out of range (the mesh has 3 vertices, indexed from 0)"},
      {"a NaN vertex", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", MeshFormat::Obj,
       "m.obj:1: a vertex coordinate is not finite ('v nan 0 0')"},
      {"an infinite vertex", "v 0 0 0\nv 1 0 0\nv 0 -inf 0\nf 1 2 3\n", MeshFormat::Obj,
       "m.obj:3: a vertex coordinate is not finite ('v 0 -inf 0')"},
      {"a vertex past float's range", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n", MeshFormat::Obj,
       "m.obj: vertex 1 is not finite (inf, 0, 0)"},
      {"no faces", tri, MeshFormat::Obj, "m.obj: no triangles"},
      {"a PLY NaN vertex", ply_head + "0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::Ply,
       "m.ply: vertex 1 is not finite (nan, 0, 0)"},
      {"fewer vertices than the header says", ply_head + "0 0 0\n1 0 0\n3 0 1 2\n", MeshFormat::Ply,
       "m.ply: element 'face' item 0: a list of 2 values runs past the end of the file"},
      {"a negative index", ply_head + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", MeshFormat::Ply,
       "m.ply: face 0: vertex index -1 is out of range (the mesh has 3 vertices, indexed from 0)"},
      {"a header promising 10^12 faces",
       "ply\nformat binary_little_endian 1.0\nelement face 1000000000000\nproperty list uchar int vertex_indices\n"
       "end_header\n" + std::string(64, '\0'),
       MeshFormat::Ply,
       "m.ply: the header promises 1000000000000 'face' items, which take at least 1 bytes each, but the file has "
       "64 bytes after its header (a truncated binary file?)"},
      {"a binary body that ends early",
       "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
       "property float z\nend_header\n" + std::string(30, '\0'),
       MeshFormat::Ply,
       "m.ply: the header promises 3 'vertex' items, which take at least 12 bytes each, but the file has 30 "
       "bytes after its header (a truncated binary file?)"},
      {"a face list longer than the file",
       "ply\nformat binary_little_endian 1.0\nelement face 1\nproperty list uint int vertex_indices\n"
       "end_header\n" + std::string("\xff\xff\xff\x0f", 4) + std::string(8, '\0'),
       MeshFormat::Ply, "m.ply: element 'face' item 0: a list of 268435455 values runs past the end of the file"},
      {"no end_header", "ply\nformat ascii 1.0\nelement vertex 3\n", MeshFormat::Ply,
       "m.ply: header line 4: the file ends inside its header (no end_header line)"},
      {"not a PLY file", "solid x\n", MeshFormat::Ply, "m.ply: header line 1: expected 'ply', the PLY magic word"},
  };
  for (const Case& c : cases) {
    const std::string name = c.format == MeshFormat::Obj ? "m.obj" : "m.ply";
    EXPECT_EQ(mesh_error(c.bytes, c.format, name), c.message) << c.what;
  }
}

TEST(MeshFile, FilesAreCheckedBeforeTheyAreRead) {
  const TempDir dir;
  EXPECT_THROW(
      {
        try {
          tracer::load_mesh_file((dir / "missing.obj").string());
        } catch (const tracer::SceneError& e) {
          EXPECT_EQ(std::string(e.what()), (dir / "missing.obj").string() + ": no such file");
          throw;
        }
      },
      tracer::SceneError);
  fs::create_directories(dir / "folder.ply");
  try {
    tracer::load_mesh_file((dir / "folder.ply").string());
    ADD_FAILURE() << "a directory loaded";
  } catch (const tracer::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
  }
  // A 2 GB file (sparse: no disk used) is refused against the budget before a byte is read.
  const fs::path big = dir / "big.obj";
  { std::ofstream(big).put('v'); }
  fs::resize_file(big, std::uint64_t(2) << 30);
  try {
    tracer::load_mesh_file(big.string(), std::uint64_t(1) << 30);
    ADD_FAILURE() << "a 2 GB file loaded under a 1 GiB budget";
  } catch (const tracer::SceneError& e) {
    EXPECT_EQ(std::string(e.what()), "--max-memory: " + big.string() +
                                         " (2 GiB) needs about 8 GiB to load, over the memory budget of 1 GiB");
  }
  try {
    tracer::load_mesh_file((dir / "model.xyz").string());
    ADD_FAILURE();
  } catch (const tracer::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown mesh format '.xyz'"), std::string::npos) << e.what();
  }
}

TEST(MeshScene, AFileMeshIsPlacedByItsTransformAndSavedAsItsReference) {
  const TempDir dir;
  fs::create_directories(dir / "models");
  write(dir / "models" / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\n");
  const std::string scene_json = R"({
    "materials": [{"name": "m", "type": "diffuse"}],
    "meshes": [
      {"file": "models/tri.obj", "material": "m"},
      {"file": "models/tri.obj", "material": "m",
       "transform": {"translate": [10, 0, 0], "rotate": [0, 0, 90], "scale": 2}}],
    "triangles": [{"vertices": [[5, 5, 5], [6, 5, 5], [5, 6, 5]], "material": "m"}]})";
  write(dir / "scene.json", scene_json);
  const tracer::Scene s = tracer::load_scene_file((dir / "scene.json").string());
  ASSERT_EQ(s.geometry.triangles.size(), 5u);
  ASSERT_EQ(s.meshes.size(), 2u);
  // The inline triangle first (scene order: triangles before meshes), then the two copies.
  EXPECT_EQ(s.meshes[0].first_triangle, 1u);
  EXPECT_EQ(s.meshes[0].triangle_count, 2u);
  EXPECT_EQ(s.geometry.triangles[1].p1, accel::Vec3(1, 0, 0));  // identity: the file's own bits
  // Scaled by 2, turned 90 degrees about z (x -> y), moved by 10 along x.
  const accel::Vec3 p1 = s.geometry.triangles[3].p1;
  EXPECT_NEAR(p1.x, 10.0f, 1e-6f);
  EXPECT_NEAR(p1.y, 2.0f, 1e-6f);
  EXPECT_NEAR(p1.z, 0.0f, 1e-6f);
  EXPECT_EQ(s.meshes[1].stats.vertices, 4u);

  // Saved elsewhere: the meshes are references relative to the new file, not triangles.
  fs::create_directories(dir / "out");
  tracer::save_scene_file(s, (dir / "out" / "saved.json").string());
  std::ifstream in(dir / "out" / "saved.json");
  const nlohmann::json saved = nlohmann::json::parse(in);
  ASSERT_EQ(saved["meshes"].size(), 2u);
  EXPECT_EQ(saved["meshes"][0]["file"], "../models/tri.obj");
  EXPECT_EQ(saved["triangles"].size(), 1u);
  EXPECT_FALSE(saved["meshes"][0].contains("transform"));
  EXPECT_EQ(saved["meshes"][1]["transform"]["scale"], nlohmann::json({2.0, 2.0, 2.0}));
  const tracer::Scene again = tracer::load_scene_file((dir / "out" / "saved.json").string());
  ASSERT_EQ(again.geometry.triangles.size(), s.geometry.triangles.size());
  for (std::size_t i = 0; i < s.geometry.triangles.size(); ++i) {
    EXPECT_EQ(again.geometry.triangles[i].p0, s.geometry.triangles[i].p0) << i;
    EXPECT_EQ(again.geometry.triangles[i].p2, s.geometry.triangles[i].p2) << i;
  }
}

TEST(MeshScene, BadMeshEntriesNameTheirJsonPath) {
  const TempDir dir;
  write(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string head = R"({"materials": [{"name": "m", "type": "diffuse"}], "meshes": [)";
  const tracer::SceneReadContext context{dir / "" == fs::path() ? "" : (dir / "").string(), 0};
  const std::pair<std::string, std::string> cases[] = {
      {R"({"file": "nothere.obj", "material": "m"})", "/meshes/0/file: " + (dir / "nothere.obj").string() + ": no such file"},
      {R"({"file": "tri.obj", "vertices": [], "material": "m"})",
       "/meshes/0/vertices: a mesh has either \"file\" or inline vertices and indices, not both"},
      {R"({"file": "tri.obj", "material": "m", "transform": {"scale": [1, 0, 1]}})",
       "/meshes/0/transform/scale: must be non-zero on every axis, got [1,0,1]"},
      {R"({"file": "tri.obj", "material": "m", "transform": {"shear": 1}})",
       "/meshes/0/transform/shear: unknown key in transform (expected one of translate, rotate, scale)"},
      {R"({"vertices": [[0,0,0],[1,0,0],[0,1,0]], "indices": [[0,1,2]], "transform": {}, "material": "m"})",
       "/meshes/0/transform: applies to a mesh read from a \"file\" only"},
  };
  for (const auto& [mesh, message] : cases) {
    try {
      tracer::parse_scene_json(head + mesh + "]}", context);
      ADD_FAILURE() << "loaded: " << mesh;
    } catch (const tracer::SceneError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(message, 0), 0u) << e.what();
    }
  }
}

TEST(MeshScene, ConvertFramesAModelOnAFloorWithoutMovingIt) {
  if (!fs::exists(kMeshes)) GTEST_SKIP() << kMeshes << " is absent";
  const std::string teapot = (kMeshes / "teapot.obj").string();
  const tracer::Scene s = scenes_gen::scene_around_model(teapot);
  const MeshData m = tracer::load_mesh_file(teapot);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_TRUE(s.meshes[0].transform.is_identity());
  ASSERT_EQ(s.geometry.triangles.size(), m.triangles.size());
  EXPECT_EQ(s.geometry.triangles[7].p2, m.vertices[m.triangles[7][2]]);
  ASSERT_EQ(s.geometry.planes.size(), 1u);
  float lowest = 1e30f;
  for (const accel::Vec3& v : m.vertices) lowest = std::min(lowest, v.y);
  EXPECT_EQ(s.geometry.planes[0].offset, lowest);
  EXPECT_FALSE(s.lights.empty());
}

}  // namespace
