#pragma once
// The naive loop over every primitive in any scalar type, without an acceleration structure: the
// double-precision reference (precision "double") that the float renderer is measured against.
// Same queries, tie rules and primitive routines as Intersector, so in float it would give the
// naive structure's answers exactly.

#include "scene_geometry.h"
#include "intersector.h"
#include "scalar.h"

#include "accel/stats.h"

#include <cstdint>

namespace tracer {

template <class T>
class NaiveReference {
 public:
  static constexpr bool kCounting = false;  ///< No traversal counters: there is no traversal.
  using Scalar = T;                         ///< The scalar type of its rays and hits.

  NaiveReference(const Geometry& geometry, TriangleTest triangles_by)
      : geo_(&geometry), tri_(triangles_by) {}

  /// The same reference (it keeps no counters).
  NaiveReference with_counters(accel::TraversalCounters*) const { return *this; }

  /// Nearest hit in (ray.tmin, ray.tmax); ties go to the lower id, planes last.
  HitT<T> closest(RayT<T> ray) const {
    HitT<T> hit;
    for (std::uint32_t i = 0; i < geo_->planes.size(); ++i) {
      const T t = intersect(geo_->planes[i], ray);
      if (t < ray.tmax) {
        ray.tmax = t;
        hit = {t, HitT<T>::kPlaneBit | i};
      }
    }
    for (std::uint32_t id = 0, n = geo_->bounded_count(); id < n; ++id) {
      const T t = geo_->intersect_bounded(id, ray, tri_);
      if (t < ray.tmax || (t == ray.tmax && t < kInfinityOf<T> && id < hit.prim)) {
        ray.tmax = t;
        hit = {t, id};
      }
    }
    return hit;
  }

  /// True when anything lies in (ray.tmin, ray.tmax).
  bool occluded(const RayT<T>& ray) const {
    for (const Plane& pl : geo_->planes)
      if (intersect(pl, ray) < ray.tmax) return true;
    for (std::uint32_t id = 0, n = geo_->bounded_count(); id < n; ++id)
      if (geo_->intersect_bounded(id, ray, tri_) < ray.tmax) return true;
    return false;
  }

  const Geometry& geometry() const { return *geo_; }
  /// The ray/triangle routine it runs (the render's `triangle` knob).
  TriangleTest triangle_test() const { return tri_; }

 private:
  const Geometry* geo_;
  TriangleTest tri_;
};

}  // namespace tracer
