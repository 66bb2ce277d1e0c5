#pragma once
// Embree 3 as a peer structure, measured in the same run rather than reimplemented: one user
// geometry with one primitive per box, whose intersect and occluded callbacks call the caller's
// leaf function through a trampoline. Built only when Embree 3 was found
// (ACCELBENCH_HAVE_EMBREE).
//
// Embree's BVH is opaque: nodes, leaves, depth and SAH cost are not visible through its API, nor
// are nodes visited or boxes tested per ray; they are reported as 0 (see stats_note()). The
// leaf callbacks are counted, so prims_tested is exact.

#include "embree_params.h"
#include "geometry.h"
#include "interval_slack.h"
#include "stats.h"

#include <span>

#if ACCELBENCH_HAVE_EMBREE

#include <embree3/rtcore.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <utility>

namespace accel {

struct BuildLimits;

namespace embree_detail {

/// Move-only owner of an Embree handle, released with `Release`.
template <class Handle, void (*Release)(Handle)>
class RtcHandle {
 public:
  RtcHandle() = default;
  explicit RtcHandle(Handle h) : h_(h) {}
  RtcHandle(RtcHandle&& o) noexcept : h_(std::exchange(o.h_, nullptr)) {}
  RtcHandle& operator=(RtcHandle&& o) noexcept {
    if (this != &o) {
      reset();
      h_ = std::exchange(o.h_, nullptr);
    }
    return *this;
  }
  RtcHandle(const RtcHandle&) = delete;
  RtcHandle& operator=(const RtcHandle&) = delete;
  ~RtcHandle() { reset(); }

  Handle get() const { return h_; }

 private:
  void reset() {
    if (h_) Release(h_);
    h_ = nullptr;
  }
  Handle h_ = nullptr;
};

using Device = RtcHandle<RTCDevice, rtcReleaseDevice>;
using Scene = RtcHandle<RTCScene, rtcReleaseScene>;

/// What the callbacks need during one query. Embree hands the callbacks a pointer to `rtc`,
/// which is the first member of a standard-layout struct, so it converts back to the whole.
struct QueryContext {
  RTCIntersectContext rtc;  ///< Must stay first.
  Ray* rays;                ///< Our ray, or a packet's rays by id; the leaf function shortens tmax.
  unsigned count;           ///< Rays in `rays`; lanes with a larger id are not the caller's.
  void* leaf;               ///< The caller's leaf closure.
  TraversalCounters* counters;  ///< Counting pass only; else null.
  /// Calls the leaf closure for one primitive and the ray with id `lane` (one instantiation per
  /// closure type).
  bool (*test)(const QueryContext& q, unsigned lane, std::uint32_t prim);
};
static_assert(std::is_standard_layout_v<QueryContext>, "Embree's context must be the first member");

/// The single-ray leaf function (lane is 0).
template <bool Count, class LeafFn>
bool call_leaf(const QueryContext& q, unsigned lane, std::uint32_t prim) {
  if constexpr (Count) q.counters->prims_tested++;
  return (*static_cast<LeafFn*>(q.leaf))(prim, q.rays[lane]);
}

/// The packet leaf function, which takes the lane.
template <bool Count, class LeafFn>
bool call_packet_leaf(const QueryContext& q, unsigned lane, std::uint32_t prim) {
  if constexpr (Count) q.counters->prims_tested++;
  return (*static_cast<LeafFn*>(q.leaf))(std::size_t(lane), prim, q.rays[lane]);
}

/// Embree's packet types and queries of K rays (4, 8 or 16).
template <int K>
struct PacketApi;
template <>
struct PacketApi<4> {
  using RayHitK = RTCRayHit4;
  using RayK = RTCRay4;
  static void intersect(const int* v, RTCScene s, RTCIntersectContext* c, RayHitK* r) { rtcIntersect4(v, s, c, r); }
  static void occluded(const int* v, RTCScene s, RTCIntersectContext* c, RayK* r) { rtcOccluded4(v, s, c, r); }
};
template <>
struct PacketApi<8> {
  using RayHitK = RTCRayHit8;
  using RayK = RTCRay8;
  static void intersect(const int* v, RTCScene s, RTCIntersectContext* c, RayHitK* r) { rtcIntersect8(v, s, c, r); }
  static void occluded(const int* v, RTCScene s, RTCIntersectContext* c, RayK* r) { rtcOccluded8(v, s, c, r); }
};
template <>
struct PacketApi<16> {
  using RayHitK = RTCRayHit16;
  using RayK = RTCRay16;
  static void intersect(const int* v, RTCScene s, RTCIntersectContext* c, RayHitK* r) { rtcIntersect16(v, s, c, r); }
  static void occluded(const int* v, RTCScene s, RTCIntersectContext* c, RayK* r) { rtcOccluded16(v, s, c, r); }
};

/// What fills a packet's lanes past the caller's rays: an empty interval, in case Embree traces
/// a lane its valid mask turned off (see intersect_fn).
inline constexpr Ray kUnusedLane{Vec3(0.0f), 1.0f, Vec3(0.0f, 0.0f, 1.0f), 0.0f};

/// Lane i of an Embree packet of rays (RTCRay4/8/16) from `ray`. The id is the lane: Embree may
/// hand the callbacks fewer lanes than the packet, or reordered copies, so they find the
/// caller's ray by its id, never by their own lane index.
/// How a ray's interval reaches Embree: widened by the slack of interval_slack.h where our
/// callbacks decide the hits, or, where Embree's own primitives do (embree_points), made to mean
/// what it means to our routines: tmin excluded (Embree includes tnear), and for any-hit
/// queries tmax excluded too (Embree includes tfar).
enum class Interval : std::uint8_t { Widened, Closest, AnyHit };

inline float embree_tnear(const Ray& ray, Interval mode) {
  return mode == Interval::Widened ? widen_down(ray.tmin) : std::nextafter(ray.tmin, kInfinity);
}
inline float embree_tfar(const Ray& ray, Interval mode) {
  if (mode == Interval::Widened) return widen_up(ray.tmax);
  if (mode == Interval::AnyHit && ray.tmax < kInfinity) return std::nextafter(ray.tmax, -kInfinity);
  return ray.tmax;
}

template <Interval Mode = Interval::Widened, class RayK>
void fill_lane(RayK& r, std::size_t i, const Ray& ray) {
  r.org_x[i] = ray.org.x;
  r.org_y[i] = ray.org.y;
  r.org_z[i] = ray.org.z;
  r.tnear[i] = embree_tnear(ray, Mode);
  r.dir_x[i] = ray.dir.x;
  r.dir_y[i] = ray.dir.y;
  r.dir_z[i] = ray.dir.z;
  r.time[i] = 0.0f;
  r.tfar[i] = embree_tfar(ray, Mode);
  r.mask[i] = 0xffffffffu;
  r.id[i] = unsigned(i);
  r.flags[i] = 0;
}

/// A single Embree ray from `ray` (see fill_lane).
template <Interval Mode = Interval::Widened>
void fill_ray(RTCRay& r, const Ray& ray) {
  r.org_x = ray.org.x;
  r.org_y = ray.org.y;
  r.org_z = ray.org.z;
  r.tnear = embree_tnear(ray, Mode);
  r.dir_x = ray.dir.x;
  r.dir_y = ray.dir.y;
  r.dir_z = ray.dir.z;
  r.time = 0.0f;
  r.tfar = embree_tfar(ray, Mode);
  r.mask = 0xffffffffu;
  r.id = 0;
  r.flags = 0;
}

/// A K-wide packet of `rays` (at most K) for rtcOccludedK: lane i is rays[i], valid[i] is set on
/// those lanes, and the lanes past them are masked off and hold kUnusedLane.
template <Interval Mode = Interval::Widened, int K, class RayK>
void fill_packet(int (&valid)[K], RayK& r, std::span<const Ray> rays) {
  for (std::size_t i = 0; i < std::size_t(K); ++i) {
    valid[i] = i < rays.size() ? -1 : 0;
    fill_lane<Mode>(r, i, i < rays.size() ? rays[i] : kUnusedLane);
  }
}

/// fill_packet for rtcIntersectK, every lane's hit set to none.
template <Interval Mode = Interval::Widened, int K, class RayHitK>
void fill_packet_hit(int (&valid)[K], RayHitK& rh, std::span<const Ray> rays) {
  fill_packet<Mode>(valid, rh.ray, rays);
  for (std::size_t i = 0; i < std::size_t(K); ++i) {
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID[i] = RTC_INVALID_GEOMETRY_ID;
  }
}

/// The lanes [0, n) of a packet rtcOccludedK found occluded (Embree sets their tfar to -inf),
/// as bits from bit `base` on.
template <class RayK>
std::uint32_t occluded_bits(const RayK& r, std::size_t n, std::size_t base) {
  std::uint32_t bits = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (r.tfar[i] == -kInfinity) bits |= 1u << (base + i);
  return bits;
}

struct MemoryMonitor;

}  // namespace embree_detail

class EmbreeAccel {
 public:
  using Params = EmbreeParams;
  static constexpr const char* kName = "embree";
  static constexpr const char* kSummary =
      "Embree 3 user geometry calling our primitive routine (the peer we measure against)";
  /// The peer we measure against, not one of ours.
  static constexpr bool kPeer = true;

  EmbreeAccel() = default;
  /// Builds an Embree scene over `boxes` (primitive id = index). Throws knobs::ConfigError, starting
  /// with `owner`, when Embree fails or its allocations would pass the memory budget of `limits`.
  EmbreeAccel(std::span<const Aabb> boxes, const EmbreeParams& params, const BuildLimits& limits,
              const char* owner = kName);
  EmbreeAccel(EmbreeAccel&&) noexcept;
  EmbreeAccel& operator=(EmbreeAccel&&) noexcept;
  ~EmbreeAccel();

  /// Closest hit through rtcIntersect1; leaf_fn shortens ray.tmax and Embree's tfar follows.
  template <bool Count = false, class LeafFn>
  void intersect(Ray& ray, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    if constexpr (Count) counters->rays++;
    embree_detail::QueryContext q = context<Count>(ray, leaf_fn, counters);
    RTCRayHit rh;
    embree_detail::fill_ray(rh.ray, ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_.get(), &q.rtc, &rh);
  }

  /// Closest hit for each of `rays` through rtcIntersect4/8/16 (the `packet` knob), flagged
  /// coherent: Embree's packet traversal, the peer of intersect_packet in the wide BVHs.
  /// leaf_fn(lane, id, ray) takes the ray's index in `rays`.
  template <bool Count = false, class LeafFn>
  void intersect_packet(std::span<Ray> rays, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    switch (packet_lanes_) {
      case 4: return intersect_packets<4, Count>(rays, leaf_fn, counters);
      case 8: return intersect_packets<8, Count>(rays, leaf_fn, counters);
      default: return intersect_packets<16, Count>(rays, leaf_fn, counters);
    }
  }

  /// Any hit through rtcOccluded1: stops at the first primitive whose leaf_fn returns true.
  template <bool Count = false, class LeafFn>
  bool occluded(const Ray& ray_in, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    if constexpr (Count) counters->rays++;
    Ray ray = ray_in;
    embree_detail::QueryContext q = context<Count>(ray, leaf_fn, counters);
    RTCRay r;
    embree_detail::fill_ray(r, ray);
    rtcOccluded1(scene_.get(), &q.rtc, &r);
    return r.tfar == -kInfinity;
  }

  /// Any hit for each of up to 32 rays through rtcOccluded4/8/16 (the `packet` knob), flagged
  /// coherent: the peer of the wide BVHs' occluded_packet. Bit i of the result is set when
  /// rays[i] is occluded; leaf_fn(lane, id, ray) takes the ray's index in `rays`.
  template <bool Count = false, class LeafFn>
  std::uint32_t occluded_packet(std::span<const Ray> rays, LeafFn&& leaf_fn,
                                TraversalCounters* counters = nullptr) const {
    switch (packet_lanes_) {
      case 4: return occluded_packets<4, Count>(rays, leaf_fn, counters);
      case 8: return occluded_packets<8, Count>(rays, leaf_fn, counters);
      default: return occluded_packets<16, Count>(rays, leaf_fn, counters);
    }
  }

  const EmbreeParams& params() const { return params_; }
  /// For a peer built on this one (embree_points): the device, a new scene with this one's
  /// build settings, a commit that throws knobs::ConfigError on Embree's errors and on the memory
  /// budget, the bytes Embree holds now, and swapping the scene queries use for another.
  RTCDevice device() const { return device_.get(); }
  embree_detail::Scene new_scene() const;
  void commit(const embree_detail::Scene& scene) const;
  std::uint64_t allocated_bytes() const;
  void replace_scene(embree_detail::Scene scene);
  RTCScene scene() const { return scene_.get(); }
  BuildStats& mutable_stats() { return stats_; }

  /// The instruction set Embree's kernels run at.
  Isa isa() const { return isa_; }
  /// Rays per packet query.
  int packet_lanes() const { return packet_lanes_; }
  const BuildStats& stats() const { return stats_; }
  /// Which statistics Embree cannot report.
  static const char* stats_note() {
    return "embree: nodes, leaves, depth, sah_cost, nodes_visited and boxes_tested are not "
           "visible through Embree's API and are reported as 0; memory_bytes is what Embree "
           "allocated";
  }

 private:
  /// A packet leaf function seen from one group of 16: lane i of the group is ray base + i.
  template <class LeafFn>
  struct Lane {
    std::remove_reference_t<LeafFn>* leaf_fn;
    std::size_t base;
    bool operator()(std::size_t lane, std::uint32_t id, Ray& ray) const { return (*leaf_fn)(base + lane, id, ray); }
  };

  /// intersect_packet with K rays per Embree query.
  template <int K, bool Count, class LeafFn>
  void intersect_packets(std::span<Ray> rays, LeafFn& leaf_fn, TraversalCounters* counters) const {
    using Api = embree_detail::PacketApi<K>;
    for (std::size_t base = 0; base < rays.size(); base += K) {
      const std::size_t n = std::min(std::size_t(K), rays.size() - base);
      if constexpr (Count) counters->rays += n;
      Lane<LeafFn> lane_fn{&leaf_fn, base};
      embree_detail::QueryContext q = context<Count, true>(rays[base], lane_fn, counters, n);
      q.rtc.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      alignas(64) int valid[K];
      alignas(64) typename Api::RayHitK rh;
      embree_detail::fill_packet_hit(valid, rh, rays.subspan(base, n));
      Api::intersect(valid, scene_.get(), &q.rtc, &rh);
    }
  }

  /// occluded_packet with K rays per Embree query.
  template <int K, bool Count, class LeafFn>
  std::uint32_t occluded_packets(std::span<const Ray> rays_in, LeafFn& leaf_fn, TraversalCounters* counters) const {
    using Api = embree_detail::PacketApi<K>;
    std::uint32_t occluded = 0;
    for (std::size_t base = 0; base < rays_in.size() && base < 32; base += K) {
      const std::size_t n = std::min(std::size_t(K), rays_in.size() - base);
      if constexpr (Count) counters->rays += n;
      Ray rays[K];
      std::copy_n(rays_in.begin() + std::ptrdiff_t(base), n, rays);
      Lane<LeafFn> lane_fn{&leaf_fn, base};
      embree_detail::QueryContext q = context<Count, true>(rays[0], lane_fn, counters, n);
      q.rtc.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      alignas(64) int valid[K];
      alignas(64) typename Api::RayK r;
      embree_detail::fill_packet(valid, r, std::span<const Ray>(rays, n));
      Api::occluded(valid, scene_.get(), &q.rtc, &r);
      occluded |= embree_detail::occluded_bits(r, n, base);
    }
    return occluded;
  }

  /// The query's context: `rays` is the ray, or lane 0 of a packet's rays.
  template <bool Count, bool Packet = false, class LeafFn>
  static embree_detail::QueryContext context(Ray& rays, LeafFn& leaf_fn, TraversalCounters* counters,
                                             std::size_t count = 1) {
    using L = std::remove_reference_t<LeafFn>;
    embree_detail::QueryContext q;
    rtcInitIntersectContext(&q.rtc);
    q.rays = &rays;
    q.count = unsigned(count);
    q.leaf = const_cast<void*>(static_cast<const void*>(std::addressof(leaf_fn)));
    q.counters = counters;
    if constexpr (Packet)
      q.test = &embree_detail::call_packet_leaf<Count, L>;
    else
      q.test = &embree_detail::call_leaf<Count, L>;
    return q;
  }
  EmbreeParams params_;
  const char* owner_ = kName;  ///< Starts every error message.
  Isa isa_ = Isa::Sse2;    ///< The level Embree's kernels run at (params_.isa resolved).
  int packet_lanes_ = 16;  ///< Rays per packet query (params_.packet resolved).
  // Declared before the scene so that it is released after it (members die in reverse order).
  std::unique_ptr<embree_detail::MemoryMonitor> monitor_;
  embree_detail::Device device_;
  embree_detail::Scene scene_;
  BuildStats stats_;
};

}  // namespace accel

#else  // Embree 3 not found: the name is registered, and make_accel says how to get it.

namespace accel {

/// Stands in for the Embree adapter in a build without Embree 3; never constructed.
struct EmbreeAccel {
  using Params = EmbreeParams;
  static constexpr const char* kName = "embree";
  static constexpr const char* kSummary =
      "Embree 3 user geometry calling our primitive routine (the peer we measure against)";
  /// The peer we measure against, not one of ours.
  static constexpr bool kPeer = true;
  /// Why it is missing and what to do, for make_accel's error.
  static constexpr const char* kMissing = "not built (Embree 3 was not found; run scripts/setup)";
};

}  // namespace accel

#endif
