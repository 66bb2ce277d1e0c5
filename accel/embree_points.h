#pragma once
// Embree's own spheres as a second peer: RTC_GEOMETRY_TYPE_SPHERE_POINT, so Embree's traversal
// and Embree's ray-sphere routine, with no callback per primitive. Its hits are Embree's, not our
// routine's, so it is checked against naive within a tolerance (the same sphere for >= 99.9% of
// rays, t within 1e-5 relative; StructureInfo::exact is false), not bit for bit.
//
// Built over boxes alone it is the user-geometry adapter (EmbreeAccel). attach_spheres, which
// tracer::attach_geometry calls for a scene of spheres only, builds the native scene that every
// query uses from then on; its time is added to build_ms, so a render's build time counts both
// builds. A scene with other primitives stays user geometry, like `embree`.

#include "embree_accel.h"
#include "sphere_soa.h"

#if ACCELBENCH_HAVE_EMBREE

namespace accel {

class EmbreePoints {
 public:
  using Params = EmbreePointsParams;
  static constexpr const char* kName = "embree_points";
  static constexpr const char* kSummary =
      "Embree 3's own spheres (RTC_GEOMETRY_TYPE_SPHERE_POINT) and its sphere routine: a peer checked "
      "within a tolerance";
  /// The peer we measure against, not one of ours.
  static constexpr bool kPeer = true;
  /// Its hits come from Embree's sphere routine, not ours: equal to naive within a tolerance.
  static constexpr bool kExact = false;

  EmbreePoints() = default;
  EmbreePoints(std::span<const Aabb> boxes, const Params& params, const BuildLimits& limits)
      : params_(params), embree_(boxes, params, limits, kName) {
    Params::knobs().validate(params_);
  }

  /// Rebuilds the scene with `spheres` (spheres[i] is primitive i) as Embree's sphere points.
  /// Throws knobs::ConfigError on Embree's errors and the memory budget.
  void attach_spheres(std::span<const SphereShape> spheres);
  /// True once the spheres are attached: Embree's own spheres answer the queries.
  bool native() const { return native_; }

  /// Closest hit: rtcIntersect1 on the sphere points; the hit goes to leaf_fn.accept(id, t, ray)
  /// (or, for a leaf function without accept, is tested again by leaf_fn(id, ray)).
  template <bool Count = false, class LeafFn>
  void intersect(Ray& ray, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    if (!native_) return embree_.intersect<Count>(ray, leaf_fn, counters);
    if constexpr (Count) counters->rays++;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    embree_detail::fill_ray<embree_detail::Interval::Closest>(rh.ray, ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(embree_.scene(), &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return;
    if constexpr (AcceptingLeafFn<std::remove_reference_t<LeafFn>>)
      leaf_fn.accept(rh.hit.primID, rh.ray.tfar, ray);
    else
      leaf_fn(rh.hit.primID, ray);
  }

  /// Closest hits of `rays` through rtcIntersect4/8/16 (the `packet` knob), flagged coherent.
  template <bool Count = false, class LeafFn>
  void intersect_packet(std::span<Ray> rays, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    if (!native_) return embree_.intersect_packet<Count>(rays, leaf_fn, counters);
    switch (embree_.packet_lanes()) {
      case 4: return intersect_packets<4, Count>(rays, leaf_fn, counters);
      case 8: return intersect_packets<8, Count>(rays, leaf_fn, counters);
      default: return intersect_packets<16, Count>(rays, leaf_fn, counters);
    }
  }

  /// Any hit through rtcOccluded1.
  template <bool Count = false, class LeafFn>
  bool occluded(const Ray& ray, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    if (!native_) return embree_.occluded<Count>(ray, leaf_fn, counters);
    if constexpr (Count) counters->rays++;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r;
    embree_detail::fill_ray<embree_detail::Interval::AnyHit>(r, ray);
    rtcOccluded1(embree_.scene(), &context, &r);
    return r.tfar == -kInfinity;
  }

  /// Any hit of up to 32 rays through rtcOccluded4/8/16; bit i set when rays[i] is occluded.
  template <bool Count = false, class LeafFn>
  std::uint32_t occluded_packet(std::span<const Ray> rays, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    if (!native_) return embree_.occluded_packet<Count>(rays, leaf_fn, counters);
    switch (embree_.packet_lanes()) {
      case 4: return occluded_packets<4, Count>(rays, counters);
      case 8: return occluded_packets<8, Count>(rays, counters);
      default: return occluded_packets<16, Count>(rays, counters);
    }
  }

  const Params& params() const { return params_; }
  const BuildStats& stats() const { return embree_.stats(); }
  /// The instruction set Embree's kernels run at.
  Isa isa() const { return embree_.isa(); }
  static const char* stats_note() {
    return "embree_points: nodes, leaves, depth, sah_cost, nodes_visited, boxes_tested and (on its own "
           "spheres) prims_tested are not visible through Embree's API and are reported as 0; build_ms "
           "counts the user-geometry build over the boxes and the sphere-point build after it";
  }

 private:
  template <int K, bool Count, class LeafFn>
  void intersect_packets(std::span<Ray> rays, LeafFn& leaf_fn, TraversalCounters* counters) const {
    using Api = embree_detail::PacketApi<K>;
    for (std::size_t base = 0; base < rays.size(); base += K) {
      const std::size_t n = std::min(std::size_t(K), rays.size() - base);
      if constexpr (Count) counters->rays += n;
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      alignas(64) int valid[K];
      alignas(64) typename Api::RayHitK rh;
      for (std::size_t i = 0; i < std::size_t(K); ++i) {
        valid[i] = i < n ? -1 : 0;
        embree_detail::fill_lane<embree_detail::Interval::Closest>(rh.ray, i, i < n ? rays[base + i] : embree_detail::kUnusedLane);
        rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
      }
      Api::intersect(valid, embree_.scene(), &context, &rh);
      for (std::size_t i = 0; i < n; ++i) {
        if (rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
        if constexpr (AcceptingPacketLeafFn<LeafFn>)
          leaf_fn.accept(base + i, rh.hit.primID[i], rh.ray.tfar[i], rays[base + i]);
        else
          leaf_fn(base + i, rh.hit.primID[i], rays[base + i]);
      }
    }
  }

  template <int K, bool Count>
  std::uint32_t occluded_packets(std::span<const Ray> rays, TraversalCounters* counters) const {
    using Api = embree_detail::PacketApi<K>;
    std::uint32_t occluded = 0;
    for (std::size_t base = 0; base < rays.size() && base < 32; base += K) {
      const std::size_t n = std::min(std::size_t(K), rays.size() - base);
      if constexpr (Count) counters->rays += n;
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      alignas(64) int valid[K];
      alignas(64) typename Api::RayK r;
      for (std::size_t i = 0; i < std::size_t(K); ++i) {
        valid[i] = i < n ? -1 : 0;
        embree_detail::fill_lane<embree_detail::Interval::AnyHit>(r, i, i < n ? rays[base + i] : embree_detail::kUnusedLane);
      }
      Api::occluded(valid, embree_.scene(), &context, &r);
      for (std::size_t i = 0; i < n; ++i)
        if (r.tfar[i] == -kInfinity) occluded |= 1u << (base + i);
    }
    return occluded;
  }

  Params params_;
  EmbreeAccel embree_;   ///< The device, and the user-geometry scene until spheres are attached.
  bool native_ = false;  ///< The scene holds Embree's sphere points.
};

}  // namespace accel

#else  // Embree 3 not found

namespace accel {

/// Stands in for embree_points in a build without Embree 3; never constructed.
struct EmbreePoints {
  using Params = EmbreePointsParams;
  static constexpr const char* kName = "embree_points";
  static constexpr const char* kSummary =
      "Embree 3's own spheres (RTC_GEOMETRY_TYPE_SPHERE_POINT) and its sphere routine: a peer checked "
      "within a tolerance";
  /// The peer we measure against, not one of ours.
  static constexpr bool kPeer = true;
  static constexpr bool kExact = false;
  static constexpr const char* kMissing = "not built (Embree 3 was not found; run scripts/setup)";
};

}  // namespace accel

#endif
