#include "triangle_box.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace tracer {

bool triangle_touches_box(const Triangle& tri, const accel::Aabb& cell, double margin) {
  const glm::dvec3 c = 0.5 * (glm::dvec3(cell.lo) + glm::dvec3(cell.hi));
  const glm::dvec3 h = 0.5 * (glm::dvec3(cell.hi) - glm::dvec3(cell.lo)) + margin;
  const glm::dvec3 v[3] = {glm::dvec3(tri.p0) - c, glm::dvec3(tri.p1) - c, glm::dvec3(tri.p2) - c};
  // Rounding in double is far below the margin; a small extra slack on every comparison keeps
  // the test on the safe side anyway.
  const auto separated = [&](const glm::dvec3& axis) {
    const double p0 = glm::dot(v[0], axis), p1 = glm::dot(v[1], axis), p2 = glm::dot(v[2], axis);
    const double r = h.x * std::abs(axis.x) + h.y * std::abs(axis.y) + h.z * std::abs(axis.z);
    const double slack = 1e-12 * (r + std::abs(p0) + std::abs(p1) + std::abs(p2));
    return std::min({p0, p1, p2}) > r + slack || std::max({p0, p1, p2}) < -r - slack;
  };
  // The box's faces.
  for (int a = 0; a < 3; ++a) {
    glm::dvec3 axis(0.0);
    axis[a] = 1.0;
    if (separated(axis)) return false;
  }
  // The triangle's plane.
  const glm::dvec3 e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  if (separated(glm::cross(e[0], e[1]))) return false;
  // The nine edge-by-axis cross products.
  for (const glm::dvec3& edge : e)
    for (int a = 0; a < 3; ++a) {
      glm::dvec3 unit(0.0);
      unit[a] = 1.0;
      const glm::dvec3 axis = glm::cross(edge, unit);
      if (axis != glm::dvec3(0.0) && separated(axis)) return false;
    }
  return true;
}

namespace {

bool touches(const void* context, std::uint32_t id, const accel::Aabb& cell) {
  const Geometry& g = *static_cast<const Geometry*>(context);
  if (g.kind_of(id) != PrimitiveKind::Triangle) return true;
  const double size = double(std::max({cell.hi.x - cell.lo.x, cell.hi.y - cell.lo.y, cell.hi.z - cell.lo.z}));
  const double far = double(std::max({std::abs(cell.lo.x), std::abs(cell.lo.y), std::abs(cell.lo.z),
                                      std::abs(cell.hi.x), std::abs(cell.hi.y), std::abs(cell.hi.z)}));
  return triangle_touches_box(g.triangles[id - g.first_id[1]], cell, 0x1p-16 * (size + far));
}

}  // namespace

accel::PrimitiveOverlap primitive_overlap(const Geometry& geometry) {
  if (geometry.triangles.empty()) return {};
  return {&geometry, touches};
}

}  // namespace tracer
