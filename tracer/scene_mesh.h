#pragma once
// Placing a mesh in a scene: its triangles in world space appended to the geometry, and the
// reference to its file recorded (Scene::meshes), as a scene file's "meshes" entry and the mesh
// generators do it.

#include "mesh_file.h"
#include "mesh_instance.h"
#include "scene.h"

namespace tracer {

/// Appends `mesh` placed by `instance.transform` to scene.geometry.triangles with
/// `instance.material`, and records the instance with its triangle range and stats (a triangle
/// that rounds to zero area in world space is dropped and counted as degenerate). Call
/// geometry.finalize() after the last change.
void add_mesh(Scene& scene, const MeshData& mesh, MeshInstance instance);

/// The bytes the scene's triangles take, the triangle records and their bounds.
std::uint64_t triangle_bytes(const Geometry& geometry);

}  // namespace tracer
