#include "scene_geometry.h"

#include "rounding.h"

namespace tracer {

namespace {

/// The box grown by one ulp outward on every side. Each primitive's bounds are rounded to
/// nearest at most once per coordinate (centre +- radius), so one step down for lo and one up
/// for hi always contains the exact box: a sphere whose radius is below half an ulp of its
/// centre keeps a box around its surface instead of collapsing onto its centre.
accel::Aabb rounded_outward(const accel::Aabb& b) {
  accel::Aabb out;
  for (int a = 0; a < 3; ++a) {
    out.lo[a] = next_down(b.lo[a]);
    out.hi[a] = next_up(b.hi[a]);
  }
  return out;
}

}  // namespace

std::vector<accel::Aabb> Geometry::primitive_bounds() const {
  std::vector<accel::Aabb> out;
  out.reserve(bounded_count());
  for (const Sphere& s : spheres) out.push_back(rounded_outward(bounds(s)));
  for (const Triangle& t : triangles) out.push_back(rounded_outward(bounds(t)));
  for (const Box& b : boxes) out.push_back(rounded_outward(bounds(b)));
  for (const Cone& c : cones) out.push_back(rounded_outward(bounds(c)));
  for (const Polygon& p : polygons) out.push_back(rounded_outward(bounds(p, polygon_vertices.data())));
  return out;
}

}  // namespace tracer
