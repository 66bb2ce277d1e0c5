#pragma once
// What the integrator needs to know about a hit: where, how far from the true surface that
// point may be, which way the surface faces, and its material.
//
// Every primitive kind returns its hit point with a conservative absolute error bound per
// coordinate (pbrt-v4, Pharr, Jakob and Humphreys, ch. 6.8): some point of the exact surface lies
// within p +- p_error. Secondary rays leave from p moved along the geometric normal by exactly
// that bound (tracer/offset_ray.h), which is a few ulps of the coordinates involved at any scale.
// Sphere, plane, polygon and cone points are re-projected onto their surface and triangle points
// are barycentric, so the bound does not grow with the ray's length.

#include "geometry.h"
#include "intersector.h"

#include <cstdint>

namespace tracer {

struct SurfacePoint {
  Vec3 p{0.0f};        ///< Hit point, world units.
  Vec3 p_error{0.0f};  ///< Bound on |p - q| per coordinate for some point q of the exact surface, world units.
  Vec3 n_geo{0.0f};    ///< Outward unit geometric normal (front side for planes and triangles).
  Vec3 n_shade{0.0f};  ///< Unit shading normal: n_geo, or the interpolated vertex normal.
  std::uint32_t material = 0;  ///< Index into Scene::materials.
};

/// The surface point of `hit` (which must be found()) on the ray it came from.
SurfacePoint surface_point(const Geometry& geometry, const Ray& ray, const Hit& hit);

}  // namespace tracer
