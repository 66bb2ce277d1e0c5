#pragma once
// What the integrator needs to know about a hit: where, which way the surface faces, and its
// material. Hit points are re-projected onto the surface so that their error is a few ulps of
// the surface's own coordinates, which is what offset_ray_origin() is built for.

#include "geometry.h"
#include "intersector.h"

#include <cstdint>

namespace tracer {

struct SurfacePoint {
  Vec3 p{0.0f};        ///< Hit point on the surface, world units.
  Vec3 n_geo{0.0f};    ///< Outward unit geometric normal (front side for planes and triangles).
  Vec3 n_shade{0.0f};  ///< Unit shading normal: n_geo, or the interpolated vertex normal.
  std::uint32_t material = 0;  ///< Index into Scene::materials.
};

/// The surface point of `hit` (which must be found()) on the ray it came from.
SurfacePoint surface_point(const Geometry& geometry, const Ray& ray, const Hit& hit);

}  // namespace tracer
