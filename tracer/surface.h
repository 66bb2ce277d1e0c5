#pragma once
// What the integrator needs to know about a hit: where, how far from the true surface that
// point may be, which way the surface faces, and its material.
//
// Every primitive kind returns its hit point with a conservative absolute error bound per
// coordinate (pbrt-v4, Pharr, Jakob and Humphreys, ch. 6.8): some point of the exact surface lies
// within p +- p_error. Secondary rays leave from p moved along the geometric normal by exactly
// that bound (tracer/offset_ray.h), which is a few ulps of the coordinates involved at any scale.
// Sphere, plane, polygon and cone points are re-projected onto their surface and triangle points
// are barycentric, so the bound does not grow with the ray's length. Written once for the scalar
// type T (float, double: tracer/scalar.h).

#include "scene_geometry.h"
#include "intersector.h"
#include "scalar.h"

#include <cstdint>

namespace tracer {

template <class T>
struct SurfacePointT {
  Vec3T<T> p{T(0)};        ///< Hit point, world units.
  Vec3T<T> p_error{T(0)};  ///< Bound on |p - q| per coordinate for some point q of the exact surface, world units.
  Vec3T<T> n_geo{T(0)};    ///< Outward unit geometric normal (front side for planes and triangles).
  Vec3T<T> n_shade{T(0)};  ///< Unit shading normal: n_geo, or the interpolated vertex normal.
  std::uint32_t material = 0;  ///< Index into Scene::materials.
};
using SurfacePoint = SurfacePointT<float>;
using SurfacePointD = SurfacePointT<double>;

/// The surface point of `hit` (which must be found()) on the ray it came from; a triangle's by
/// the routine that found the hit.
SurfacePoint surface_point(const Geometry& geometry, const Ray& ray, const Hit& hit, TriangleTest triangles_by);
/// The same in double precision (the naive reference).
SurfacePointD surface_point(const Geometry& geometry, const RayD& ray, const HitD& hit, TriangleTest triangles_by);

}  // namespace tracer
