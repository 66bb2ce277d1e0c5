#pragma once
// Closed triangle meshes whose neighbours share their vertices exactly: the subdivided
// icosahedron (tessellated spheres) and a cube whose faces are grids of triangle pairs. Rays
// aimed at their shared edges and vertices test that a triangle routine never leaks.

#include "tracer/mesh_file.h"

namespace scenes_gen {

/// Triangles of an icosphere of `subdivisions` levels: 20 * 4^subdivisions.
inline std::uint64_t icosphere_triangles(int subdivisions) { return std::uint64_t(20) << (2 * subdivisions); }

/// The unit icosphere: an icosahedron whose triangles are split in four `subdivisions` times, every
/// vertex pushed onto the unit sphere (in double, rounded once). Outward counter-clockwise.
tracer::MeshData icosphere(int subdivisions);

/// The cube [-1, 1]^3 with each face a `cells` x `cells` grid of squares, each split into two
/// triangles; vertices on shared edges are one vertex. Outward counter-clockwise.
tracer::MeshData grid_cube(int cells);

}  // namespace scenes_gen
