#pragma once
// The scene's primitives, grouped by kind, and the one routine every structure calls to test one.
//
// Bounded primitives get global ids in kind order (spheres, triangles, boxes, cones, polygons);
// the acceleration structures see only those ids and their boxes. Planes are unbounded and are
// tested by the tracer beside the structure, identically for every structure.

#include "box.h"
#include "cone.h"
#include "plane.h"
#include "polygon.h"
#include "sphere.h"
#include "triangle.h"

#include "accel/geometry.h"

#include <array>
#include <cstdint>
#include <vector>

namespace tracer {

/// The kinds of bounded primitive, in global-id order.
enum class PrimitiveKind : std::uint8_t { Sphere, Triangle, Box, Cone, Polygon, Count };

/// Which kinds a scene uses; the render loop is specialised on it so that a scene pays only for
/// the kinds it has ("model only what a scene requires").
enum class KindSet : std::uint8_t { SpheresOnly, Mixed };

struct Geometry {
  std::vector<Sphere> spheres;
  std::vector<Triangle> triangles;
  std::vector<Box> boxes;
  std::vector<Cone> cones;              ///< Truncated cones and cylinders without caps.
  std::vector<Polygon> polygons;        ///< Planar polygons with 4 or more vertices.
  std::vector<Vec3> polygon_vertices;   ///< Vertices of all polygons (Polygon::first_vertex).
  std::vector<Plane> planes;            ///< Unbounded; not in the acceleration structures.
  std::vector<Vec3> vertex_normals;     ///< Three per smooth triangle (Triangle::normals).
  /// Take the Mixed dispatch even when every primitive is a sphere: only for measuring what the
  /// SpheresOnly fast path saves (same binary, same scene).
  bool force_mixed = false;

  /// First global id of each kind; call finalize() after changing the arrays.
  std::array<std::uint32_t, std::size_t(PrimitiveKind::Count) + 1> first_id{};

  void finalize() {
    first_id[0] = 0;
    first_id[1] = first_id[0] + std::uint32_t(spheres.size());
    first_id[2] = first_id[1] + std::uint32_t(triangles.size());
    first_id[3] = first_id[2] + std::uint32_t(boxes.size());
    first_id[4] = first_id[3] + std::uint32_t(cones.size());
    first_id[5] = first_id[4] + std::uint32_t(polygons.size());
  }
  std::uint32_t bounded_count() const { return first_id.back(); }
  KindSet kind_set() const {
    return !force_mixed && bounded_count() == spheres.size() ? KindSet::SpheresOnly : KindSet::Mixed;
  }
  PrimitiveKind kind_of(std::uint32_t id) const {
    if (id < first_id[1]) return PrimitiveKind::Sphere;
    if (id < first_id[2]) return PrimitiveKind::Triangle;
    if (id < first_id[3]) return PrimitiveKind::Box;
    if (id < first_id[4]) return PrimitiveKind::Cone;
    return PrimitiveKind::Polygon;
  }

  /// Bounding box of every bounded primitive, indexed by global id, rounded outward by one ulp
  /// so that it contains the exact primitive at any coordinate.
  std::vector<accel::Aabb> primitive_bounds() const;

  /// Distance t > ray.tmin to bounded primitive `id`, or +inf, in the ray's scalar type (Ray:
  /// float, RayD: double), triangles by the routine `triangles_by`. Pure function of (id, org,
  /// dir, tmin, routine), so every structure gets bit-identical distances.
  template <KindSet Kinds = KindSet::Mixed, class R = Ray>
  ScalarOf<R> intersect_bounded(std::uint32_t id, const R& ray, TriangleTest triangles_by) const {
    if constexpr (Kinds == KindSet::SpheresOnly) {
      return intersect(spheres[id], ray);
    } else {
      if (id < first_id[1]) return intersect(spheres[id], ray);
      if (id < first_id[2]) return intersect(triangles[id - first_id[1]], ray, triangles_by);
      if (id < first_id[3]) return intersect(boxes[id - first_id[2]], ray);
      if (id < first_id[4]) return intersect(cones[id - first_id[3]], ray);
      return intersect_polygon(polygons[id - first_id[4]], polygon_vertices.data(), ray);
    }
  }
};

}  // namespace tracer
