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

bool clip_triangle_to_box(const Triangle& tri, const accel::Aabb& cell, double margin, accel::Aabb& part) {
  // A triangle clipped by six planes has at most 9 vertices in exact arithmetic; rounding can make
  // a polygon whose edge lies in a plane cross it more than twice, so the arrays have room to
  // spare, and a polygon that would outgrow them keeps the triangle's whole box (conservative).
  constexpr int kRoom = 16;
  glm::dvec3 poly[kRoom] = {glm::dvec3(tri.p0), glm::dvec3(tri.p1), glm::dvec3(tri.p2)};
  glm::dvec3 next[kRoom];
  int count = 3;
  for (int axis = 0; axis < 3 && count > 0; ++axis)
    for (int side = 0; side < 2 && count > 0; ++side) {
      if (2 * count > kRoom) {
        count = 3;
        poly[0] = glm::dvec3(tri.p0), poly[1] = glm::dvec3(tri.p1), poly[2] = glm::dvec3(tri.p2);
        axis = 3;  // stop clipping
        break;
      }
      // Keep sign * (x - plane) >= 0: x >= lo - margin, then x <= hi + margin.
      const double sign = side == 0 ? 1.0 : -1.0;
      const double plane = side == 0 ? double(cell.lo[axis]) - margin : double(cell.hi[axis]) + margin;
      int kept = 0;
      for (int i = 0; i < count; ++i) {
        const glm::dvec3& a = poly[i];
        const glm::dvec3& b = poly[(i + 1) % count];
        const double da = sign * (a[axis] - plane), db = sign * (b[axis] - plane);
        if (da >= 0.0) next[kept++] = a;
        if ((da >= 0.0) != (db >= 0.0)) {
          glm::dvec3 x = a + (b - a) * (da / (da - db));
          x[axis] = plane;  // exactly on the plane, whatever the rounding of the interpolation
          next[kept++] = x;
        }
      }
      std::copy(next, next + kept, poly);
      count = kept;
    }
  if (count == 0) return false;
  glm::dvec3 lo = poly[0], hi = poly[0];
  for (int i = 1; i < count; ++i) {
    lo = glm::min(lo, poly[i]);
    hi = glm::max(hi, poly[i]);
  }
  // The margin (2^-16 of the cell's scale where the trees call this) dwarfs the rounding of the
  // interpolation and of the conversion to float.
  part = {accel::Vec3(lo - margin), accel::Vec3(hi + margin)};
  return true;
}

namespace {

/// The overlap margin for `cell`: 2^-16 of its size and of its distance from the origin.
double margin_of(const accel::Aabb& cell) {
  const double size = double(std::max({cell.hi.x - cell.lo.x, cell.hi.y - cell.lo.y, cell.hi.z - cell.lo.z}));
  const double far = double(std::max({std::abs(cell.lo.x), std::abs(cell.lo.y), std::abs(cell.lo.z),
                                      std::abs(cell.hi.x), std::abs(cell.hi.y), std::abs(cell.hi.z)}));
  return 0x1p-16 * (size + far);
}

bool touches(const void* context, std::uint32_t id, const accel::Aabb& cell) {
  const Geometry& g = *static_cast<const Geometry*>(context);
  if (g.kind_of(id) != PrimitiveKind::Triangle) return true;
  return triangle_touches_box(g.triangles[id - g.first_id[1]], cell, margin_of(cell));
}

accel::Aabb clip(const void* context, std::uint32_t id, const accel::Aabb& box, const accel::Aabb& cell) {
  const accel::Aabb in_cell{glm::max(box.lo, cell.lo), glm::min(box.hi, cell.hi)};
  const Geometry& g = *static_cast<const Geometry*>(context);
  if (g.kind_of(id) != PrimitiveKind::Triangle) return in_cell;
  accel::Aabb part;
  // touches() may keep a triangle that the clip finds outside the widened cell (its margins
  // differ slightly); the box then stands.
  if (!clip_triangle_to_box(g.triangles[id - g.first_id[1]], cell, margin_of(cell), part)) return in_cell;
  return {glm::max(part.lo, in_cell.lo), glm::min(part.hi, in_cell.hi)};
}

}  // namespace

accel::PrimitiveOverlap primitive_overlap(const Geometry& geometry) {
  if (geometry.triangles.empty()) return {};
  return {&geometry, touches, clip};
}

}  // namespace tracer
