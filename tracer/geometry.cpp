#include "geometry.h"

namespace tracer {

std::vector<accel::Aabb> Geometry::primitive_bounds() const {
  std::vector<accel::Aabb> out;
  out.reserve(bounded_count());
  for (const Sphere& s : spheres) out.push_back(bounds(s));
  for (const Triangle& t : triangles) out.push_back(bounds(t));
  for (const Box& b : boxes) out.push_back(bounds(b));
  for (const Cone& c : cones) out.push_back(bounds(c));
  for (const Polygon& p : polygons) out.push_back(bounds(p, polygon_vertices.data()));
  return out;
}

}  // namespace tracer
