#pragma once
// The properties every mesh loader's fuzz target checks (fuzz_mesh_obj, fuzz_mesh_ply).

#include "fuzz_check.h"

#include "tracer/mesh_file.h"
#include "tracer/scene_error.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <string>

namespace fuzz {

inline void check_mesh(const std::uint8_t* data, std::size_t size, tracer::MeshFormat format,
                       const std::string& name) {
  tracer::MeshData mesh;
  try {
    mesh = tracer::parse_mesh(text_of(data, size), format, name);
  } catch (const tracer::SceneError& e) {
    check_message(e.what(), name + ":");
    return;
  }
  require(!mesh.triangles.empty(), "a mesh that loads has triangles", name);
  require(mesh.stats.triangles == mesh.triangles.size(), "stats count the triangles kept", name);
  for (const accel::Vec3& p : mesh.vertices)
    require(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z), "every vertex is finite", name);
  for (const auto& t : mesh.triangles) {
    for (const std::uint32_t i : t) require(i < mesh.vertices.size(), "every index is in range", name);
    const glm::dvec3 a(mesh.vertices[t[0]]), b(mesh.vertices[t[1]]), c(mesh.vertices[t[2]]);
    require(glm::cross(b - a, c - a) != glm::dvec3(0.0), "no zero-area triangle is kept", name);
  }
}

}  // namespace fuzz
