#include "scene_mesh.h"

#include <glm/geometric.hpp>

namespace tracer {

void add_mesh(Scene& scene, const MeshData& mesh, MeshInstance instance) {
  Geometry& g = scene.geometry;
  std::vector<Vec3> world(mesh.vertices.size());
  for (std::size_t i = 0; i < world.size(); ++i) world[i] = instance.transform.apply(mesh.vertices[i]);
  instance.stats = mesh.stats;
  instance.first_triangle = std::uint32_t(g.triangles.size());
  g.triangles.reserve(g.triangles.size() + mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    const Triangle tri{world[t[0]], world[t[1]], world[t[2]], instance.material, -1};
    if (glm::cross(glm::dvec3(tri.p1) - glm::dvec3(tri.p0), glm::dvec3(tri.p2) - glm::dvec3(tri.p0)) ==
        glm::dvec3(0.0)) {
      ++instance.stats.degenerate;
      --instance.stats.triangles;
      continue;
    }
    g.triangles.push_back(tri);
  }
  instance.triangle_count = std::uint32_t(g.triangles.size() - instance.first_triangle);
  scene.meshes.push_back(std::move(instance));
}

std::uint64_t triangle_bytes(const Geometry& geometry) {
  return geometry.triangles.size() * (sizeof(Triangle) + sizeof(accel::Aabb));
}

}  // namespace tracer
