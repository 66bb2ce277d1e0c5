#pragma once
// Closest-hit and any-hit queries of a scene's geometry through one acceleration structure.
//
// This is where the traversal contract meets the primitives: the structure calls the leaf
// function with a global primitive id, and the leaf function runs the one shared primitive
// routine. Unbounded planes are tested here, beside the structure, the same way for all.
// with_intersector() dispatches once per render on (structure, kinds, counting), so each
// combination's loops are compiled on their own, with no virtual call per node or primitive.

#include "scene_geometry.h"

#include "accel/accel.h"
#include "accel/cache_line_allocator.h"

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <variant>
#include <vector>

namespace tracer {

/// Result of a closest-hit query, in the scalar type T of the ray.
template <class T>
struct HitT {
  static constexpr std::uint32_t kNone = 0xffffffffu;
  static constexpr std::uint32_t kPlaneBit = 0x80000000u;  ///< Set on ids of unbounded planes.

  T t = kInfinityOf<T>;         ///< Hit distance along the ray, in units of |dir|.
  std::uint32_t prim = kNone;   ///< Global bounded id, or kPlaneBit | plane index.

  bool found() const { return prim != kNone; }
  bool is_plane() const { return found() && (prim & kPlaneBit) != 0; }
};
using Hit = HitT<float>;
using HitD = HitT<double>;

template <KindSet Kinds, bool Count, class Structure>
class Intersector {
 public:
  static constexpr bool kCounting = Count;
  using Scalar = float;  ///< The scalar type of its rays and hits.

  Intersector(const Geometry& geometry, const Structure& structure, TriangleTest triangles_by,
              accel::TraversalCounters* counters = nullptr)
      : geo_(&geometry), structure_(&structure), counters_(counters), tri_(triangles_by) {}

  /// The same intersector writing its counters elsewhere (one set per thread).
  Intersector with_counters(accel::TraversalCounters* counters) const {
    return Intersector(*geo_, *structure_, tri_, counters);
  }

  /// Nearest hit in (ray.tmin, ray.tmax). Ties in t go to the lower id, so every structure
  /// reports the same primitive whatever order it visits them in.
  Hit closest(Ray ray) const {
    Hit hit = closest_plane(ray);
    ClosestLeaf leaf{geo_, tri_, &hit};
    structure_->template intersect<Count>(ray, leaf, counters_);
    return hit;
  }

  /// Rays closest() takes at once: a tile of camera rays.
  static constexpr std::size_t kPacketMax = 16;

  /// closest(rays[i]) into hits[i] for up to kPacketMax rays, bit for bit. A structure that
  /// traverses packets (intersect_packet) takes them together; the others one at a time.
  void closest_packet(std::span<const Ray> rays, std::span<Hit> hits) const {
    Ray packet[kPacketMax];
    const std::size_t n = std::min(rays.size(), kPacketMax);
    for (std::size_t i = 0; i < n; ++i) {
      packet[i] = rays[i];
      hits[i] = closest_plane(packet[i]);
    }
    if constexpr (requires(PacketLeaf& leaf) {
                    structure_->template intersect_packet<Count>(std::span<Ray>(packet, n), leaf, counters_);
                  }) {
      PacketLeaf leaf{geo_, tri_, hits.data()};
      structure_->template intersect_packet<Count>(std::span<Ray>(packet, n), leaf, counters_);
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        ClosestLeaf leaf{geo_, tri_, &hits[i]};
        structure_->template intersect<Count>(packet[i], leaf, counters_);
      }
    }
  }

  /// True when anything lies in (ray.tmin, ray.tmax).
  bool occluded(const Ray& ray) const {
    if (occluded_by_plane(ray)) return true;
    AnyLeaf leaf{geo_, tri_};
    return structure_->template occluded<Count>(ray, leaf, counters_);
  }

  /// occluded(rays[i]) in bit i, for up to kPacketMax rays (the shadow rays of a tile's camera
  /// hits toward one light). A structure that traverses packets (occluded_packet) takes the
  /// rays no plane occludes together; the others one at a time.
  std::uint32_t occluded_packet(std::span<const Ray> rays) const {
    const std::size_t n = std::min(rays.size(), kPacketMax);
    std::uint32_t occluded = 0;
    Ray open[kPacketMax];  // the rays no plane occludes, and their indices in `rays`
    std::uint32_t index[kPacketMax];
    std::size_t m = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (occluded_by_plane(rays[i])) {
        occluded |= 1u << i;
        continue;
      }
      open[m] = rays[i];
      index[m++] = std::uint32_t(i);
    }
    if (m == 0) return occluded;
    std::uint32_t bits = 0;
    if constexpr (requires(PacketAnyLeaf& leaf) {
                    structure_->template occluded_packet<Count>(std::span<const Ray>(open, m), leaf, counters_);
                  }) {
      PacketAnyLeaf leaf{geo_, tri_};
      bits = structure_->template occluded_packet<Count>(std::span<const Ray>(open, m), leaf, counters_);
    } else {
      for (std::size_t k = 0; k < m; ++k) {
        AnyLeaf leaf{geo_, tri_};
        if (structure_->template occluded<Count>(open[k], leaf, counters_)) bits |= 1u << k;
      }
    }
    for (; bits; bits &= bits - 1u) occluded |= 1u << index[std::countr_zero(bits)];
    return occluded;
  }

  const Geometry& geometry() const { return *geo_; }
  /// The ray/triangle routine its leaf tests run (the render's `triangle` knob).
  TriangleTest triangle_test() const { return tri_; }

 private:
  // The leaf functions of the traversal contract. accept() takes a t the structure computed
  // itself: with the same routine (SIMD sphere and triangle leaves, accel/sphere_soa.h and
  // accel/triangle_soa.h, which hold spheres only in sphere-only scenes and triangles only in
  // triangle-only ones, and run the routine triangle_test() names), or with its own (Embree's
  // primitives, a peer within a tolerance).

  /// Closest hit: keeps the nearest, ties to the lower id.
  struct ClosestLeaf {
    const Geometry* geo;
    TriangleTest tri;
    Hit* hit;
    bool keep(std::uint32_t id, float t, Ray& r) const {
      // Plane ids carry kPlaneBit, so at an exact tie a bounded primitive wins over a plane.
      if (t < r.tmax || (t == r.tmax && t < accel::kInfinity && id < hit->prim)) {
        r.tmax = t;
        *hit = {t, id};
        return true;
      }
      return false;
    }
    bool operator()(std::uint32_t id, Ray& r) const { return keep(id, geo->template intersect_bounded<Kinds>(id, r, tri), r); }
    bool accept(std::uint32_t id, float t, Ray& r) const
    {
      return keep(id, t, r);
    }
    TriangleTest triangle_test() const { return tri; }
  };

  /// ClosestLeaf for the ray of each lane of a packet, writing hits[lane].
  struct PacketLeaf {
    const Geometry* geo;
    TriangleTest tri;
    Hit* hits;
    bool operator()(std::size_t lane, std::uint32_t id, Ray& r) const { return ClosestLeaf{geo, tri, hits + lane}(id, r); }
    bool accept(std::size_t lane, std::uint32_t id, float t, Ray& r) const
    {
      return ClosestLeaf{geo, tri, hits + lane}.keep(id, t, r);
    }
    TriangleTest triangle_test() const { return tri; }
  };

  /// The nearest unbounded plane in the ray's interval, which shortens ray.tmax to it.
  Hit closest_plane(Ray& ray) const {
    Hit hit;
    for (std::uint32_t i = 0; i < geo_->planes.size(); ++i) {
      const float t = intersect(geo_->planes[i], ray);
      if (t < ray.tmax) {
        ray.tmax = t;
        hit = {t, Hit::kPlaneBit | i};
      }
    }
    return hit;
  }

  /// True when an unbounded plane lies in the ray's interval.
  bool occluded_by_plane(const Ray& ray) const {
    for (const Plane& pl : geo_->planes)
      if (intersect(pl, ray) < ray.tmax) return true;
    return false;
  }

  /// Any hit: anything before tmax.
  struct AnyLeaf {
    const Geometry* geo;
    TriangleTest tri;
    bool operator()(std::uint32_t id, Ray& r) const { return geo->template intersect_bounded<Kinds>(id, r, tri) < r.tmax; }
    bool accept(std::uint32_t, float t, Ray& r) const
    {
      return t < r.tmax;
    }
    TriangleTest triangle_test() const { return tri; }
  };

  /// AnyLeaf for the ray of any lane of a packet.
  struct PacketAnyLeaf {
    const Geometry* geo;
    TriangleTest tri;
    bool operator()(std::size_t, std::uint32_t id, Ray& r) const { return AnyLeaf{geo, tri}(id, r); }
    bool accept(std::size_t, std::uint32_t, float t, Ray& r) const
    {
      return t < r.tmax;
    }
    TriangleTest triangle_test() const { return tri; }
  };

  const Geometry* geo_;
  const Structure* structure_;
  accel::TraversalCounters* counters_;
  TriangleTest tri_;
};

/// Every bounded primitive of `geometry` is a sphere (attach_geometry attaches them).
inline bool sphere_only(const Geometry& geometry) {
  return geometry.bounded_count() == geometry.spheres.size() && !geometry.spheres.empty();
}

/// Every bounded primitive of `geometry` is a triangle (attach_geometry attaches them to the
/// structures that take them).
inline bool triangle_only(const Geometry& geometry) {
  return geometry.bounded_count() == geometry.triangles.size() && !geometry.triangles.empty();
}

/// Gives a structure built over geometry.primitive_bounds() what it needs of the primitives
/// themselves: the spheres of a sphere-only scene, for structures with SIMD sphere leaves and
/// embree_points; the triangles of a triangle-only scene, for a structure that tests them itself
/// (embree_triangles, and bvh4 and bvh8 with their SIMD triangle leaves). The triangles are copied
/// only for such a structure, into a scratch array on huge pages (accel/huge_pages.h: on a
/// million triangles its page faults were 5% of a build's time on a VM).
inline void attach_geometry(accel::AnyAccel& a, const Geometry& geometry) {
  if (sphere_only(geometry)) {
    std::vector<accel::SphereShape, accel::CacheLineAllocator<accel::SphereShape>> shapes;
    shapes.reserve(geometry.spheres.size());
    for (const Sphere& s : geometry.spheres) shapes.push_back({s.center, s.radius});
    accel::attach_spheres(a, shapes);
  } else if (triangle_only(geometry) && accel::takes_triangles(a)) {
    std::vector<accel::TriangleShape, accel::CacheLineAllocator<accel::TriangleShape>> shapes;
    shapes.reserve(geometry.triangles.size());
    for (const Triangle& t : geometry.triangles) shapes.push_back({t.p0, t.p1, t.p2});
    accel::attach_triangles(a, shapes);
  }
}

/// Calls fn(intersector) with the intersector specialised for this structure, this scene's kind
/// set and the counting flag Count, testing triangles by `triangles_by`. Everything fn
/// instantiates is compiled once per combination (the triangle routine is a predictable branch
/// per test). A caller that never counts names Count and compiles half the loops.
template <bool Count, class Fn>
decltype(auto) with_intersector(const Geometry& geometry, const accel::AnyAccel& any, TriangleTest triangles_by,
                                Fn&& fn) {
  return std::visit(
      [&](const auto& structure) -> decltype(auto) {
        using S = std::decay_t<decltype(structure)>;
        if (geometry.kind_set() == KindSet::SpheresOnly)
          return fn(Intersector<KindSet::SpheresOnly, Count, S>(geometry, structure, triangles_by));
        return fn(Intersector<KindSet::Mixed, Count, S>(geometry, structure, triangles_by));
      },
      any.variant());
}

/// with_intersector<Count> with the counting flag chosen at run time.
template <class Fn>
decltype(auto) with_intersector(const Geometry& geometry, const accel::AnyAccel& any,
                                bool counting, TriangleTest triangles_by, Fn&& fn) {
  if (counting) return with_intersector<true>(geometry, any, triangles_by, fn);
  return with_intersector<false>(geometry, any, triangles_by, fn);
}

}  // namespace tracer
