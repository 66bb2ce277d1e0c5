#pragma once
// Triangle meshes from model files: OBJ through tinyobjloader, PLY (ASCII and binary, faces and
// triangle strips) through our reader (tracer/ply_reader.h says why), glTF and the other formats
// assimp reads through assimp. Polygons are split
// into triangles, zero-area triangles are dropped and counted, and every count and index is
// checked before anything is allocated from it (docs/scene-format.md, "Meshes").

#include "accel/geometry.h"

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tracer {

/// What a mesh file held, for --stats and results rows.
struct MeshStats {
  std::uint64_t file_bytes = 0;  ///< Size of the file read.
  std::uint64_t vertices = 0;    ///< Vertices in the file.
  std::uint64_t triangles = 0;   ///< Triangles kept (polygons and strips split).
  std::uint64_t degenerate = 0;  ///< Zero-area triangles dropped (repeated or collinear vertices).
};

/// A mesh as read: shared vertices and triangles of three vertex indices.
struct MeshData {
  std::vector<accel::Vec3> vertices;                 ///< Positions, the model's own units.
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< Vertex indices, counter-clockwise.
  MeshStats stats;
};

/// The file formats a mesh is read from, by extension.
enum class MeshFormat : std::uint8_t { Obj, Ply, Assimp };

/// The format of `path` by its extension; throws SceneError naming the extensions read.
MeshFormat mesh_format_of(const std::string& path);

/// Bytes a mesh file of `file_bytes` may take to load: the text, the library's arrays and ours.
std::uint64_t mesh_load_bytes(std::uint64_t file_bytes);

/// Reads the mesh at `path`. `max_memory_bytes` is the --max-memory budget (0 = 25% of RAM): a
/// file whose load would exceed it is refused before a byte is read. Throws SceneError, one line
/// starting with the path: missing, a directory, empty, truncated, an index out of range, a
/// vertex that is not finite, a count the file cannot hold.
MeshData load_mesh_file(const std::string& path, std::uint64_t max_memory_bytes = 0);

/// Parses a mesh file already in memory (the fuzz targets' entry); `name` starts each message.
MeshData parse_mesh(std::string_view bytes, MeshFormat format, const std::string& name);

}  // namespace tracer
