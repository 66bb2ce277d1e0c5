#pragma once
// The body of a PLY file: vertex positions, faces (split into fans) and triangle strips (-1
// restarts a strip; every other triangle is flipped to keep the winding), ASCII or binary of either
// byte order. Other elements and properties are read past.
//
// Our own reader, not assimp's: Debian 12's assimp 5.2.5 keeps one triangle per `tristrips`
// element (it sizes its face array by the element count), so igea.ply, one strip of 268k
// triangles, loads as a single triangle. tests/mesh_file_test.cpp checks that this reader and
// assimp agree on faces.

#include "ply_header.h"

#include "accel/geometry.h"

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tracer {

/// What a PLY body holds, unchecked: indices as written (tracer/mesh_file.cpp checks them).
struct PlyMesh {
  std::vector<accel::Vec3> vertices;
  std::vector<std::array<std::int64_t, 3>> triangles;
  std::uint64_t short_faces = 0;  ///< Faces of fewer than three vertices, skipped.
};

/// Reads the body of `bytes` after `header` (read_ply_header). Throws SceneError "<name>: ..."
/// when it ends early, a value does not parse, or the vertex element lacks x, y or z.
PlyMesh read_ply_body(std::string_view bytes, const PlyHeader& header, const std::string& name);

}  // namespace tracer
