#pragma once
// A mesh a scene reads from a model file: the file, where it is placed (translate, rotate, scale)
// and its material. The scene refers to the file rather than copying it: its triangles are
// loaded into Geometry::triangles, and a saved scene writes the reference back.

#include "mesh_file.h"

#include "accel/geometry.h"

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <string>

namespace tracer {

/// Model to world: p -> translate + rotate(scale * p), the rotation about x, then y, then z.
struct MeshTransform {
  glm::dvec3 translate{0.0};  ///< World units.
  glm::dvec3 rotate{0.0};     ///< Degrees about x, y and z, applied in that order.
  glm::dvec3 scale{1.0};      ///< Per axis, non-zero.

  bool is_identity() const { return translate == glm::dvec3(0.0) && rotate == glm::dvec3(0.0) && scale == glm::dvec3(1.0); }
  /// The linear part, rotate * scale, in double.
  glm::dmat3 linear() const;
  /// A model point in world space: computed in double, rounded once to float; exact for identity.
  accel::Vec3 apply(const accel::Vec3& p) const;
};

struct MeshInstance {
  std::string path;            ///< The file it was read from, as the loader opened it.
  MeshTransform transform;     ///< Model to world.
  std::uint32_t material = 0;  ///< Index into Scene::materials.
  std::uint32_t first_triangle = 0;  ///< Its triangles: Geometry::triangles[first, first + count).
  std::uint32_t triangle_count = 0;
  MeshStats stats;             ///< What the file held; degenerate counts those world space adds too.
};

}  // namespace tracer
