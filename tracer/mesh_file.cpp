#include "mesh_file.h"

#include "ply_header.h"
#include "ply_reader.h"
#include "scene_error.h"

#include "accel/build_limits.h"
#include "input/error.h"
#include "input/file_read.h"
#include "input/message.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <system_error>

namespace tracer {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string show_point(const accel::Vec3& p) {
  std::ostringstream o;
  o << '(' << p.x << ", " << p.y << ", " << p.z << ')';
  return o.str();
}

/// Checks the vertices and indices, then keeps the triangles of non-zero area (decided exactly:
/// the cross product of float edges in double).
class MeshBuilder {
 public:
  explicit MeshBuilder(const std::string& name) : name_(name) {}

  void vertex(const accel::Vec3& p) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw SceneError(name_ + ": vertex " + std::to_string(mesh_.vertices.size()) + " is not finite " +
                       show_point(p));
    mesh_.vertices.push_back(p);
  }

  /// A triangle of vertex indices as the file gives them (OBJ's are 0-based once tinyobjloader
  /// has resolved them; negative or past the end is an error).
  void triangle(std::int64_t a, std::int64_t b, std::int64_t c, std::uint64_t face) {
    const std::int64_t n = std::int64_t(mesh_.vertices.size());
    for (const std::int64_t i : {a, b, c})
      if (i < 0 || i >= n)
        throw SceneError(name_ + ": face " + std::to_string(face) + ": vertex index " + std::to_string(i) +
                         " is out of range (the mesh has " + std::to_string(n) + " vertices, indexed from 0)");
    const std::array<std::uint32_t, 3> t{std::uint32_t(a), std::uint32_t(b), std::uint32_t(c)};
    const glm::dvec3 p0(mesh_.vertices[t[0]]), p1(mesh_.vertices[t[1]]), p2(mesh_.vertices[t[2]]);
    if (glm::cross(p1 - p0, p2 - p0) == glm::dvec3(0.0)) {
      ++mesh_.stats.degenerate;
      return;
    }
    mesh_.triangles.push_back(t);
  }

  std::size_t vertex_count() const { return mesh_.vertices.size(); }

  MeshData finish(std::uint64_t file_bytes) {
    mesh_.stats.file_bytes = file_bytes;
    mesh_.stats.vertices = mesh_.vertices.size();
    mesh_.stats.triangles = mesh_.triangles.size();
    if (mesh_.triangles.empty())
      throw SceneError(name_ + ": no triangles" +
                       (mesh_.stats.degenerate ? " (all " + std::to_string(mesh_.stats.degenerate) +
                                                     " have zero area)"
                                               : std::string()));
    return std::move(mesh_);
  }

 private:
  std::string name_;
  MeshData mesh_;
};

/// tinyobjloader reads "nan" and "inf" as 0: they are refused here first, with their line.
void refuse_non_finite_obj_vertices(std::string_view bytes, const std::string& name) {
  std::size_t line = 0, pos = 0;
  while (pos < bytes.size()) {
    std::size_t end = bytes.find('\n', pos);
    if (end == std::string_view::npos) end = bytes.size();
    ++line;
    const std::string_view l = bytes.substr(pos, end - pos);
    pos = end + 1;
    if (l.size() < 2 || l[0] != 'v' || (l[1] != ' ' && l[1] != '\t')) continue;
    for (std::size_t i = 1; i < l.size(); ++i) {
      const char c = char(std::tolower(static_cast<unsigned char>(l[i])));
      if ((c == 'n' || c == 'i') && i + 2 < l.size()) {
        const std::string word = lower(std::string(l.substr(i, 3)));
        if (word == "nan" || word == "inf")
          throw SceneError(name + ":" + std::to_string(line) + ": a vertex coordinate is not finite ('" +
                           input::one_line(l, 60) + "')");
      }
    }
  }
}

MeshData parse_obj(std::string_view bytes, const std::string& name) {
  refuse_non_finite_obj_vertices(bytes, name);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;  // polygons as fans; quads by their shorter diagonal
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // No material file: the scene gives the mesh its material.
  if (!reader.ParseFromString(std::string(bytes), std::string(), config)) {
    const std::string why = input::one_line(reader.Error(), 300);
    throw SceneError(name + ": " + (why.empty() ? "not a valid OBJ file" : why));
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  MeshBuilder b(name);
  const std::size_t n = attrib.vertices.size() / 3;
  for (std::size_t i = 0; i < n; ++i)
    b.vertex({attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]});
  std::uint64_t face = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const std::vector<tinyobj::index_t>& idx = shape.mesh.indices;
    std::size_t at = 0;
    for (const unsigned int count : shape.mesh.num_face_vertices) {
      if (count != 3 || at + 3 > idx.size())
        throw SceneError(name + ": face " + std::to_string(face) + " has " + std::to_string(count) +
                         " vertices after triangulation");
      b.triangle(idx[at].vertex_index, idx[at + 1].vertex_index, idx[at + 2].vertex_index, face);
      at += count;
      ++face;
    }
  }
  return b.finish(bytes.size());
}

MeshData parse_ply(std::string_view bytes, const std::string& name) {
  const PlyHeader header = read_ply_header(bytes, name);  // counts the body cannot hold refused
  const PlyMesh ply = read_ply_body(bytes, header, name);
  MeshBuilder b(name);
  for (const accel::Vec3& p : ply.vertices) b.vertex(p);
  std::uint64_t face = 0;
  for (const auto& t : ply.triangles) b.triangle(t[0], t[1], t[2], face++);
  return b.finish(bytes.size());
}

MeshData parse_with_assimp(std::string_view bytes, const std::string& name) {
  Assimp::Importer importer;
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const std::string ext = lower(std::filesystem::path(name).extension().string());
  const aiScene* scene = importer.ReadFileFromMemory(
      bytes.data(), bytes.size(),
      aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_PreTransformVertices,
      ext.size() > 1 ? ext.c_str() + 1 : "");
  if (!scene || !scene->mRootNode) {
    const std::string why = input::one_line(importer.GetErrorString(), 300);
    throw SceneError(name + ": " + (why.empty() ? "cannot be read" : why));
  }
  MeshBuilder b(name);
  std::uint64_t face = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    const std::int64_t first = std::int64_t(b.vertex_count());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v)
      b.vertex({mesh->mVertices[v].x, mesh->mVertices[v].y, mesh->mVertices[v].z});
    for (unsigned f = 0; f < mesh->mNumFaces; ++f, ++face) {
      const aiFace& af = mesh->mFaces[f];
      if (af.mNumIndices != 3) continue;  // points and lines: not surfaces
      b.triangle(first + af.mIndices[0], first + af.mIndices[1], first + af.mIndices[2], face);
    }
  }
  return b.finish(bytes.size());
}

}  // namespace

MeshFormat mesh_format_of(const std::string& path) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  if (ext == ".obj") return MeshFormat::Obj;
  if (ext == ".ply") return MeshFormat::Ply;
  if (ext == ".gltf" || ext == ".glb" || ext == ".stl" || ext == ".off" || ext == ".fbx" || ext == ".dae" ||
      ext == ".3ds")
    return MeshFormat::Assimp;
  throw SceneError(path + ": unknown mesh format '" + ext +
                   "' (expected .obj, .ply, .gltf, .glb, .stl, .off, .fbx, .dae or .3ds)");
}

std::uint64_t mesh_load_bytes(std::uint64_t file_bytes) {
  // The text, the parser's arrays (a float or an index per few characters) and our triangles
  // (44 bytes per triangle of about 30 characters): four times the file is a safe estimate.
  return 4 * file_bytes + (std::uint64_t(1) << 16);
}

MeshData parse_mesh(std::string_view bytes, MeshFormat format, const std::string& name) {
  if (bytes.empty()) throw SceneError(name + ": is empty");
  if (format == MeshFormat::Obj) return parse_obj(bytes, name);
  if (format == MeshFormat::Ply) return parse_ply(bytes, name);
  return parse_with_assimp(bytes, name);
}

MeshData load_mesh_file(const std::string& path, std::uint64_t max_memory_bytes) {
  const MeshFormat format = mesh_format_of(path);
  const std::uint64_t budget = accel::memory_budget_bytes(accel::BuildLimits{.max_memory_bytes = max_memory_bytes, .overlap = {}});
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) throw SceneError(path + ": no such file");
  if (std::filesystem::is_regular_file(status)) {
    const std::uint64_t size = std::filesystem::file_size(path, ec);
    if (!ec && mesh_load_bytes(size) > budget)
      throw SceneError("--max-memory: " + path + " (" + input::byte_text(size) + ") needs about " +
                       input::byte_text(mesh_load_bytes(size)) + " to load, over the memory budget of " +
                       input::byte_text(budget));
  }
  std::string bytes;
  try {
    // The limit holds even when the file grows after the check above.
    bytes = input::read_file(path, std::max<std::uint64_t>(budget / 4, 1), "mesh file");
  } catch (const input::InputError& e) {
    throw SceneError(e.what());
  }
  return parse_mesh(bytes, format, path);
}

}  // namespace tracer
