#pragma once
// What Embree's own primitives (embree_points, embree_triangles) share: built over boxes alone
// they are the user-geometry adapter (EmbreeAccel); once the primitives are attached, a native
// scene answers every query through Embree's traversal and Embree's primitive routine, with no
// callback per primitive. Their hits are Embree's, not our routine's, so they are checked against
// naive within a tolerance (StructureInfo::exact is false), not bit for bit.
//
// The hit goes to the leaf function's accept(id, t, ray) where it has one, else the primitive is
// tested again by leaf_fn(id, ray).

#include "embree_accel.h"
#include "ray_packet.h"
#include "sphere_soa.h"

#if ACCELBENCH_HAVE_EMBREE

#include <chrono>

namespace accel {

class EmbreeNative {
 public:
  EmbreeNative() = default;
  EmbreeNative(std::span<const Aabb> boxes, const EmbreeParams& params, const BuildLimits& limits, const char* owner)
      : embree_(boxes, params, limits, owner) {}

  /// True once the primitives are attached: Embree's own primitives answer the queries.
  bool native() const { return native_; }

  /// Closest hit through rtcIntersect1.
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

  const BuildStats& stats() const { return embree_.stats(); }
  /// The instruction set Embree's kernels run at.
  Isa isa() const { return embree_.isa(); }

 protected:
  /// A new scene with the adapter's build settings, for the peer to fill with its primitives.
  embree_detail::Scene new_scene() const { return embree_.new_scene(); }
  RTCDevice device() const { return embree_.device(); }
  /// Checks that `count` primitives are attached to a structure over as many, else throws
  /// std::invalid_argument naming `what`.
  void check_count(std::size_t count, const char* owner, const char* what) const;
  /// Commits `scene` (throws knobs::ConfigError on Embree's errors and the memory budget) and
  /// makes it answer every query. build_ms becomes the time since `start` (the native build
  /// alone, not the user-geometry build before it); memory_bytes what Embree holds now.
  void make_native(embree_detail::Scene scene, std::chrono::steady_clock::time_point start);

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
      embree_detail::fill_packet_hit<embree_detail::Interval::Closest>(valid, rh, rays.subspan(base, n));
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
      embree_detail::fill_packet<embree_detail::Interval::AnyHit>(valid, r, rays.subspan(base, n));
      Api::occluded(valid, embree_.scene(), &context, &r);
      occluded |= embree_detail::occluded_bits(r, n, base);
    }
    return occluded;
  }

  EmbreeAccel embree_;   ///< The device, and the user-geometry scene until the primitives are attached.
  bool native_ = false;  ///< The scene holds Embree's own primitives.
};

/// A registered native peer with the parameter struct P (the Embree knobs under its own name):
/// what embree_points and embree_triangles add to EmbreeNative alike.
template <class P>
class EmbreeNativePeer : public EmbreeNative {
 public:
  using Params = P;
  /// The peer we measure against, not one of ours.
  static constexpr bool kPeer = true;
  /// Its hits come from Embree's own routine, not ours: equal to naive within a tolerance.
  static constexpr bool kExact = false;

  EmbreeNativePeer() = default;
  EmbreeNativePeer(std::span<const Aabb> boxes, const P& params, const BuildLimits& limits, const char* owner)
      : EmbreeNative(boxes, params, limits, owner), params_(params) {
    P::knobs().validate(params_);
  }
  const P& params() const { return params_; }

 private:
  P params_;
};

}  // namespace accel

#else  // Embree 3 not found

namespace accel {

/// Stands in for a native peer in a build without Embree 3; never constructed.
template <class P>
struct EmbreeNativePeer {
  using Params = P;
  static constexpr bool kPeer = true;
  static constexpr bool kExact = false;
  static constexpr const char* kMissing = "not built (Embree 3 was not found; run scripts/setup)";
};

}  // namespace accel

#endif
