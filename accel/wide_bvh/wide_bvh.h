#pragma once
// Wide BVHs, `bvh4` and `bvh8`: W children per node, their boxes stored structure-of-arrays and
// tested against the ray in one SIMD step; closest-hit traversal visits the children front to
// back by entry distance, the any-hit traversal (shadow rays) in node order with no sorting and
// leaves first. Built directly by binned SAH (wide_bvh_builder.cpp): a node takes its range's
// SAH split, then keeps splitting its largest child until it has W; or, with spatial splits, as
// the binary BVH's SBVH collapsed into the same shape (wide_bvh_spatial.cpp). Leaves may hold their
// spheres (sphere_soa.h) or triangles (triangle_soa.h) structure-of-arrays, tested several at a
// time by the leaf function's own routine.

#include "accel/build_limits.h"
#include "accel/bvh.h"
#include "accel/geometry.h"
#include "accel/interval_slack.h"
#include "knobs/knob_table.h"
#include "accel/leaf_boxes.h"
#include "accel/leaf_loop.h"
#include "accel/ray_packet.h"
#include "accel/ray_setup.h"
#include "accel/simd.h"
#include "accel/sphere_soa.h"
#include "accel/triangle_soa.h"
#include "accel/stats.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <new>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace accel {

/// What each registered width is called and starts with: one registry entry per
/// specialisation (a width without one does not compile, rather than borrowing a name).
template <int W>
struct WideBvhWidth;
template <>
struct WideBvhWidth<4> {
  static constexpr const char* kName = "bvh4";
  static constexpr const char* kSummary =
      "4-wide BVH, binned SAH, SoA nodes tested in one SIMD step, SIMD sphere and triangle leaves";
  static constexpr int kLeafSize = 4;  ///< Default max_leaf_size: one SIMD step of spheres or triangles.
  static constexpr float kTraversalCost = 3.0f;  ///< Default traversal_cost.
};
template <>
struct WideBvhWidth<8> {
  static constexpr const char* kName = "bvh8";
  static constexpr const char* kSummary =
      "8-wide BVH, binned SAH, SoA nodes tested in one SIMD step, SIMD sphere and triangle leaves";
  static constexpr int kLeafSize = 8;  ///< Default max_leaf_size: one SIMD step of spheres or triangles.
  /// Default traversal_cost. A leaf tests up to 8 primitives in one SIMD step, so against an
  /// 8-wide node step a primitive costs less than the binary BVH's 3 says: at 6 the SAH keeps
  /// fuller leaves and fewer nodes; set by hand, 6 beat 3 on the camera, incoherent and shadow
  /// rays of bunny, ogre and nefertiti in two runs (docs/meshes.md).
  static constexpr float kTraversalCost = 6.0f;
};

/// Knobs of a wide BVH (the same for every width; the table is owned by its width's name).
template <int W>
struct WideBvhParams {
  /// Centroid bins per axis the SAH evaluates.
  int bins = 16;
  /// A range holding more primitives than this is always split; at or below it the SAH decides
  /// between a leaf and a split.
  int max_leaf_size = WideBvhWidth<W>::kLeafSize;
  /// Deepest level of wide nodes, root = 0; a range there is a leaf whatever it holds.
  int max_depth = 64;
  /// Cost of one wide node step relative to one primitive test (the SAH's C_trav / C_isect).
  float traversal_cost = WideBvhWidth<W>::kTraversalCost;
  /// Threads the build may use (0 = every core). The tree is the same at any count.
  int build_threads = 1;
  /// Extra references per primitive that spatial splits may add (0: none): the binary BVH's
  /// spatial-split build, collapsed into wide nodes (wide_bvh_spatial.cpp), on one thread.
  float spatial_split_budget = 0.0f;

  /// Name, range, unit and doc line of every knob above.
  static const knobs::KnobTable<WideBvhParams>& knobs();
};

/// W children per node, structure-of-arrays: the boxes' six planes (lo x, hi x, lo y, hi y,
/// lo z, hi z), each as W floats, then the children. An unused slot has an empty box (+inf,
/// -inf), which no ray enters.
template <int W>
struct alignas(64) WideNode {
  float planes[6][W];          ///< Child boxes: planes[2 a][i] lo, planes[2 a + 1][i] hi on axis a.
  std::uint32_t child[W];      ///< Inner child: node index; leaf: first index into the ids.
  std::uint32_t count[W];      ///< Leaf: primitives (> 0); inner child or unused slot: 0.
};
static_assert(sizeof(WideNode<4>) == 128, "a 4-wide node is two cache lines");
static_assert(sizeof(WideNode<8>) == 256, "an 8-wide node is four cache lines");

template <int W>
class WideBvh {
 public:
  using Params = WideBvhParams<W>;
  using Node = WideNode<W>;
  static constexpr const char* kName = WideBvhWidth<W>::kName;
  static constexpr const char* kSummary = WideBvhWidth<W>::kSummary;
  /// Traversal stack entries: a node pushes at most W - 1 children, 64 levels deep.
  static constexpr int kStackSize = (W - 1) * 64 + 1;

  WideBvh() = default;
  /// Builds over `boxes` (primitive id = index). Throws knobs::ConfigError for a bad knob or when the
  /// build would pass the memory budget of `limits`.
  WideBvh(std::span<const Aabb> boxes, const Params& params, const BuildLimits& limits);
  explicit WideBvh(std::span<const Aabb> boxes, const Params& params = {});

  /// Stores the spheres of a sphere-only scene (spheres[i] is primitive i) beside the leaves, so
  /// that leaves test them in SIMD for leaf functions that accept a precomputed t.
  /// The time it takes is added to stats().build_ms.
  void attach_spheres(std::span<const SphereShape> spheres) {
    stats_.memory_bytes -= leaf_boxes_.memory_bytes();
    leaf_boxes_.clear();  // sphere leaves test the spheres themselves
    attach_sphere_leaves(kName, prim_ids_, leaf_ranges(), spheres, spheres_, stats_);
  }

  /// Stores the triangles of a triangle-only scene (triangles[i] is primitive i) beside the
  /// leaves, so that leaves test them in SIMD, by the leaf function's routine, for leaf functions
  /// that accept a precomputed t and name their routine (TriangleLeafFn). The time it takes is
  /// added to stats().build_ms. Runs on the build's threads (knob build_threads).
  void attach_triangles(std::span<const TriangleShape> triangles);

  /// Closest hit: children front to back by entry distance; leaf_fn may shorten ray.tmax, and a
  /// child entered beyond it is skipped.
  template <bool Count = false, class LeafFn>
  void intersect(Ray& ray, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    if constexpr (Count) counters->rays++;
    if (nodes_.empty()) return;
    SingleQuery<Count, std::remove_reference_t<LeafFn>> q{*this, ray, NodeRay(RaySetup(ray)), leaf_fn, counters};
    closest<Count>(q, counters);
  }

  /// Any hit: true at the first primitive whose leaf_fn returns true. No ordering: a node's
  /// leaves are tested before its inner children are pushed.
  template <bool Count = false, class LeafFn>
  bool occluded(const Ray& ray_in, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    if constexpr (Count) counters->rays++;
    if (nodes_.empty()) return false;
    Ray ray = ray_in;
    const RaySetup rs(ray);
    return any_hit<Count>(ray, NodeRay(rs), leaf_fn, counters);
  }

  /// Closest hit for a packet of rays (coherent rays: a tile of camera rays), each ray getting
  /// the hit intersect() gives it. Groups of up to kGroup (16) rays whose directions share their
  /// signs go down the tree as one frustum: per axis the range of their origins and inverse
  /// directions bounds every ray's slab distances (IEEE rounding is monotone), so a child is
  /// entered when the bounds say any ray may enter it, and leaf spheres are tested against the
  /// group's rays simd::FloatPacket::size at a time. A group whose rays do not share their signs
  /// tries the same per packet of simd::FloatPacket::size rays, and a packet that fails too goes
  /// ray by ray. With fewer lanes than 16 (AVX2: 8, SSE2: 4) one walk serves several packets.
  /// leaf_fn(lane, id, ray) and leaf_fn.accept(lane, id, t, ray) take the ray's index in `rays`.
  template <bool Count = false, class LeafFn>
  void intersect_packet(std::span<Ray> rays, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    using L = std::remove_reference_t<LeafFn>;
    for (std::size_t base = 0; base < rays.size(); base += kGroup) {
      const std::span<Ray> group = rays.subspan(base, std::min(kGroup, rays.size() - base));
      if constexpr (Count) counters->rays += group.size();
      if (nodes_.empty()) continue;
      const PacketGroup packets(group);
      PacketFrustum frustum;
      if (packets.bound(frustum)) {
        PacketQuery<Count, L> q{*this, group, packets, frustum, base, leaf_fn, counters};
        closest<Count>(q, counters);
        continue;
      }
      for (std::size_t g = 0; g < packets.count; ++g) {
        const std::size_t first = g * kPacket;
        const std::span<Ray> part = group.subspan(first, std::min(kPacket, group.size() - first));
        const PacketGroup one(part);
        if (packets.count > 1 && one.bound(frustum)) {
          PacketQuery<Count, L> q{*this, part, one, frustum, base + first, leaf_fn, counters};
          closest<Count>(q, counters);
          continue;
        }
        for (std::size_t i = 0; i < part.size(); ++i) {
          LaneLeaf<L> lane{&leaf_fn, base + first + i};
          SingleQuery<Count, LaneLeaf<L>> q{*this, part[i], NodeRay(RaySetup(part[i])), lane, counters};
          closest<Count>(q, counters);
        }
      }
    }
  }

  /// Any hit for a packet of up to 32 rays (the shadow rays of a tile's camera hits toward one
  /// light): bit i of the result is set when rays[i] is occluded, as occluded(rays[i]) says.
  /// Groups of up to simd::FloatPacket::size rays go down the tree together, unordered like
  /// occluded() (any_hit_packet); trees with SIMD sphere leaves take the rays one by one, and
  /// with SIMD triangle leaves each ray that enters a leaf tests its triangles several at a time.
  template <bool Count = false, class LeafFn>
  std::uint32_t occluded_packet(std::span<const Ray> rays, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    using L = std::remove_reference_t<LeafFn>;
    std::uint32_t occluded = 0;
    for (std::size_t base = 0; base < rays.size() && base < 32; base += kPacket) {
      const std::size_t n = std::min(kPacket, rays.size() - base);
      if constexpr (Count) counters->rays += n;
      if (nodes_.empty()) continue;
      Ray group[kPacket];
      std::copy_n(rays.begin() + std::ptrdiff_t(base), n, group);
      std::uint32_t bits = 0;
      const RayPacket<PacketBatch> packet(std::span<const Ray>(group, n));
      if (spheres_.empty()) {
        bits = any_hit_packet<Count>(std::span<Ray>(group, n), packet, base, leaf_fn, counters);
      } else {
        for (std::size_t i = 0; i < n; ++i) {
          LaneLeaf<L> lane{&leaf_fn, base + i};
          if (any_hit<Count>(group[i], NodeRay(RaySetup(group[i])), lane, counters)) bits |= 1u << i;
        }
      }
      occluded |= bits << base;
    }
    return occluded;
  }

  const Params& params() const { return params_; }
  const BuildStats& stats() const { return stats_; }
  /// The nodes, root first. Empty for zero primitives.
  std::span<const Node> nodes() const { return nodes_; }
  /// Original primitive ids in leaf order; a leaf covers [child, child + count).
  std::span<const std::uint32_t> prim_ids() const { return prim_ids_; }
  /// True when the leaves hold their spheres structure-of-arrays.
  bool has_sphere_leaves() const { return !spheres_.empty(); }
  /// True when the leaves hold their triangles structure-of-arrays.
  bool has_triangle_leaves() const { return !triangles_.empty(); }

 private:
  /// The batch the box test runs on: W lanes where the target has them, else 4 at a time.
  using Batch = std::conditional_t<std::is_void_v<simd::FloatN<W>>, simd::Float4, simd::FloatN<W>>;
  static constexpr int kSteps = W / int(Batch::size);

  /// Per-ray data of the SIMD slab test: which plane row is near and far on each axis.
  struct NodeRay {
    float org[3];
    float inv_dir[3];
    float inv_far[3];  ///< inv_dir * (1 + 2 gamma(3)) for far distances (Ize 2013).
    int near_row[3];   ///< planes row of the near plane on each axis (lo unless the ray goes down).
    [[gnu::always_inline]] explicit NodeRay(const RaySetup& rs) {
      for (int a = 0; a < 3; ++a) {
        org[a] = rs.org[a];
        inv_dir[a] = rs.inv_dir[a];
        inv_far[a] = rs.inv_dir[a] * kSlabFarScale;
        near_row[a] = 2 * a + rs.neg[a];
      }
    }
  };

  /// Entry distances of the ray into the children of `n` within [t_lo, t_hi]: bit i of the
  /// result is set when child i is entered, at tn[i]. Each lane performs Bvh::enter's
  /// operations: a 0 * inf = NaN slab distance leaves the interval unchanged.
  [[gnu::always_inline]] static std::uint32_t enter(const Node& n, const NodeRay& r, float t_lo, float t_hi, float* tn) {
    std::uint32_t bits = 0;
    for (int s = 0; s < kSteps; ++s) {
      const int o = s * int(Batch::size);
      Batch t0(t_lo), t1(t_hi);
      for (int a = 0; a < 3; ++a) {
        const Batch org(r.org[a]);
        const Batch t_near = (Batch::load_aligned(n.planes[r.near_row[a]] + o) - org) * Batch(r.inv_dir[a]);
        const Batch t_far = (Batch::load_aligned(n.planes[r.near_row[a] ^ 1] + o) - org) * Batch(r.inv_far[a]);
        t0 = simd::max_or_second(t_near, t0);
        t1 = simd::min_or_second(t_far, t1);
      }
      t0.store_unaligned(tn + o);
      bits |= simd::mask_bits<Batch>(t0 <= t1) << o;
    }
    return bits;
  }

  /// A child waiting on the stack.
  struct Entry {
    std::uint32_t child;  ///< Node index, or first primitive of a leaf.
    std::uint32_t count;  ///< Leaf primitives; 0 for an inner node.
    float t;              ///< Entry distance, checked against the (shorter) t_hi when popped.
    std::uint32_t box;    ///< Leaf: where its box is, W * (parent node index) + slot.
  };

  /// One ray's closest-hit query: the single-ray box test, the leaf loop, its tmax.
  template <bool Count, class LeafFn>
  struct SingleQuery {
    const WideBvh& bvh;
    Ray& ray;
    NodeRay r;
    LeafFn& leaf_fn;
    TraversalCounters* counters;
    WatertightRay tri_ray = bvh.triangles_.empty() ? WatertightRay() : WatertightRay(ray);
    bool hit = false;

    std::uint64_t rays() const { return 1; }
    float t_lo() const { return widen_down(ray.tmin); }
    float t_hi() const { return widen_up(ray.tmax); }
    std::uint32_t enter(const Node& n, float lo, float hi, float* tn) const { return WideBvh::enter(n, r, lo, hi, tn); }
    // Out of line on purpose: inlined into closest(), the leaf code's SIMD registers pushed the
    // walk's own state (the node index, the ray's broadcast terms) onto the stack, and camera
    // rays on the bunny took about 15% longer (docs/meshes.md).
    [[gnu::noinline]] void leaf(std::uint32_t first, std::uint32_t count, std::uint32_t /*box*/) {
      bvh.template leaf_loop<Count, false>(ray, r, tri_ray, first, count, leaf_fn, counters, hit);
    }
  };

  using PacketBatch = simd::FloatPacket;
  static constexpr std::size_t kPacket = PacketBatch::size;
  /// Rays that walk the tree together as one frustum in intersect_packet: 16 (a 4x4 tile), in
  /// 16 / kPacket packets of kPacket lanes.
  static constexpr std::size_t kGroup = kPacket > 16 ? kPacket : 16;
  static constexpr std::size_t kPacketsPerGroup = kGroup / kPacket;

  /// A packet leaf function seen as a single-ray one for the ray of one lane.
  template <class LeafFn>
  struct LaneLeaf {
    LeafFn* leaf_fn;
    std::size_t lane;
    bool operator()(std::uint32_t id, Ray& ray) const { return (*leaf_fn)(lane, id, ray); }
    bool accept(std::uint32_t id, float t, Ray& ray) const
      requires AcceptingPacketLeafFn<LeafFn>
    {
      return leaf_fn->accept(lane, id, t, ray);
    }
    TriangleTest triangle_test() const
      requires requires(const LeafFn& f) { f.triangle_test(); }
    {
      return leaf_fn->triangle_test();
    }
  };

  /// A group of rays bounded as a frustum: per axis the range of the origins and of the inverse
  /// directions (near and far, as NodeRay scales them), and the plane row all rays take as near.
  struct PacketFrustum {
    float org_lo[3], org_hi[3];
    float inv_lo[3], inv_hi[3];  ///< Range of RaySetup::inv_dir.
    float far_lo[3], far_hi[3];  ///< Range of inv_dir * kSlabFarScale.
    int near_row[3];
    bool one_origin;  ///< Every ray leaves from the same point (camera rays).

    /// Bounds the rays of `p` (`first`: the first packet of a group, else the ranges so far
    /// grow); false when some axis has directions of both signs or a zero component (an
    /// infinite inverse), where the ranges would bound nothing useful or make NaNs. Lanes past
    /// the packet's rays repeat its first ray, so every lane is bounded.
    bool bound(const RayPacket<PacketBatch>& p, bool first) {
      constexpr std::uint32_t all = (1u << kPacket) - 1u;
      for (int a = 0; a < 3; ++a) {
        const std::uint32_t negs = simd::mask_bits<PacketBatch>(p.neg[a]);
        if (negs != 0 && negs != all) return false;
        if (simd::mask_bits<PacketBatch>(xsimd::abs(p.inv_far[a]) < PacketBatch(kInfinity)) != all) return false;
        const int row = 2 * a + (negs != 0 ? 1 : 0);
        const float olo = simd::reduce_min(p.org[a]), ohi = simd::reduce_max(p.org[a]);
        const float ilo = simd::reduce_min(p.inv_dir[a]), ihi = simd::reduce_max(p.inv_dir[a]);
        if (first) {
          near_row[a] = row;
          org_lo[a] = olo, org_hi[a] = ohi, inv_lo[a] = ilo, inv_hi[a] = ihi;
        } else {
          if (row != near_row[a]) return false;
          org_lo[a] = std::min(org_lo[a], olo), org_hi[a] = std::max(org_hi[a], ohi);
          inv_lo[a] = std::min(inv_lo[a], ilo), inv_hi[a] = std::max(inv_hi[a], ihi);
        }
        // Rounding is monotone and the scale positive, so the range of the scaled lanes is the
        // scaled range, to the bit.
        far_lo[a] = inv_lo[a] * kSlabFarScale;
        far_hi[a] = inv_hi[a] * kSlabFarScale;
      }
      one_origin = org_lo[0] == org_hi[0] && org_lo[1] == org_hi[1] && org_lo[2] == org_hi[2];
      return true;
    }
  };

  /// Up to kGroup rays as packets of kPacket lanes: packet g holds rays [g kPacket, ...).
  struct PacketGroup {
    alignas(64) RayPacket<PacketBatch> packet[kPacketsPerGroup];
    std::size_t count = 0;  ///< Packets holding rays.

    explicit PacketGroup(std::span<const Ray> rays) {
      for (std::size_t first = 0; first < rays.size(); first += kPacket)
        new (&packet[count++]) RayPacket<PacketBatch>(rays.subspan(first, std::min(kPacket, rays.size() - first)));
    }
    /// The frustum of every ray of the group (PacketFrustum::bound).
    bool bound(PacketFrustum& f) const {
      for (std::size_t g = 0; g < count; ++g)
        if (!f.bound(packet[g], g == 0)) return false;
      return true;
    }
  };

  /// The frustum's entry into the children of `n` within [t_lo, t_hi]: bit i set when some ray
  /// of the group may enter child i, tn[i] a lower bound of their entry distances. Each ray's
  /// near slab distance (p - o) * inv in enter() lies between the products at the corners of
  /// the ranges of p - o and inv, rounding included (rounding to nearest is monotone), and its
  /// far distance likewise; so a child that some ray enters in enter() is entered here. With
  /// one origin (OneOrigin) the two differences are one and half the products are the same.
  template <bool OneOrigin>
  static std::uint32_t enter_frustum(const Node& n, const PacketFrustum& f, float t_lo, float t_hi, float* tn) {
    std::uint32_t bits = 0;
    for (int s = 0; s < kSteps; ++s) {
      const int o = s * int(Batch::size);
      Batch t0(t_lo), t1(t_hi);
      for (int a = 0; a < 3; ++a) {
        const Batch o_lo(f.org_lo[a]), o_hi(f.org_hi[a]);
        const Batch pn = Batch::load_aligned(n.planes[f.near_row[a]] + o);
        const Batch pf = Batch::load_aligned(n.planes[f.near_row[a] ^ 1] + o);
        const Batch i0(f.inv_lo[a]), i1(f.inv_hi[a]), j0(f.far_lo[a]), j1(f.far_hi[a]);
        Batch t_near, t_far;
        if constexpr (OneOrigin) {
          const Batch n0 = pn - o_lo, f0 = pf - o_lo;
          t_near = xsimd::min(n0 * i0, n0 * i1);
          t_far = xsimd::max(f0 * j0, f0 * j1);
        } else {
          const Batch n0 = pn - o_hi, n1 = pn - o_lo, f0 = pf - o_hi, f1 = pf - o_lo;
          t_near = xsimd::min(xsimd::min(n0 * i0, n0 * i1), xsimd::min(n1 * i0, n1 * i1));
          t_far = xsimd::max(xsimd::max(f0 * j0, f0 * j1), xsimd::max(f1 * j0, f1 * j1));
        }
        t0 = simd::max_or_second(t_near, t0);
        t1 = simd::min_or_second(t_far, t1);
      }
      t0.store_unaligned(tn + o);
      bits |= simd::mask_bits<Batch>(t0 <= t1) << o;
    }
    return bits;
  }

  /// A group of rays' closest-hit query through its frustum: the interval is the union of the
  /// rays' intervals, and a leaf tests every ray of the group, one packet at a time.
  template <bool Count, class LeafFn>
  struct PacketQuery {
    const WideBvh& bvh;
    std::span<Ray> group;
    const PacketGroup& packets;
    const PacketFrustum& frustum;
    std::size_t lane_base;
    LeafFn& leaf_fn;
    TraversalCounters* counters;

    std::uint64_t rays() const { return group.size(); }
    float t_lo() const {
      float lo = kInfinity;
      for (std::size_t g = 0; g < packets.count; ++g) lo = std::min(lo, simd::reduce_min(packets.packet[g].t_lo));
      return lo;
    }
    float t_hi() const {
      float hi = -kInfinity;
      for (const Ray& r : group) hi = std::max(hi, widen_up(r.tmax));
      return hi;
    }
    std::uint32_t enter(const Node& n, float lo, float hi, float* tn) const {
      return frustum.one_origin ? enter_frustum<true>(n, frustum, lo, hi, tn)
                                : enter_frustum<false>(n, frustum, lo, hi, tn);
    }
    void leaf(std::uint32_t first, std::uint32_t count, std::uint32_t box) {
      for (std::size_t g = 0; g < packets.count; ++g) {
        const std::size_t at = g * kPacket;
        leaf_of(packets.packet[g], group.subspan(at, std::min(kPacket, group.size() - at)), lane_base + at, first,
                count, box);
      }
    }

    /// The leaf [first, first + count) against the rays of one packet.
    void leaf_of(const RayPacket<PacketBatch>& packet, std::span<Ray> rays, std::size_t base, std::uint32_t first,
                 std::uint32_t count, std::uint32_t box) {
      // The rays' current t_hi, lane by lane (lanes past the rays repeat the first).
      const auto hi_now = [&] {
        alignas(64) float hi[kPacket];
        for (std::size_t i = 0; i < kPacket; ++i) hi[i] = widen_up(rays[i < rays.size() ? i : 0].tmax);
        return PacketBatch::load_aligned(hi);
      };
      if constexpr (AcceptingPacketLeafFn<LeafFn>) {
        if (!bvh.spheres_.empty()) {
          bvh.spheres_.template test_packet<Count>(bvh.prim_ids_.data(), first, count, packet.valid, packet, rays,
                                                   base, leaf_fn, counters);
          return;
        }
      }
      if constexpr (TriangleLeafFn<LaneLeaf<LeafFn>>) {
        if (!bvh.triangles_.empty()) {
          // Triangle leaves: each ray of the packet that enters the leaf's box (the frustum only
          // says that some ray may) against the leaf's triangles, several at a time, as its own
          // walk would test them.
          const std::uint32_t in =
              enter_rays(bvh.nodes_[box / std::uint32_t(W)], int(box % std::uint32_t(W)), packet, hi_now());
          for (std::uint32_t lanes = in; lanes; lanes &= lanes - 1u) {
            const std::size_t i = std::size_t(std::countr_zero(lanes));
            LaneLeaf<LeafFn> lane{&leaf_fn, base + i};
            bool hit = false;
            bvh.triangles_.template test<Count, false>(bvh.prim_ids_.data(), first, count, rays[i],
                                                       WatertightRay(rays[i]), lane, counters, hit);
          }
          return;
        }
      }
      // Each primitive's box against every ray (the rays' current t_hi), then the leaf function
      // for the rays that may enter it. Leaves of up to kOrdered primitives take them in the
      // order of the least entry distance into their boxes, and test each box against the rays'
      // hits so far, so that a near hit spares the farther primitives behind it.
      const auto test = [&](std::uint32_t j, std::uint32_t lanes) {
        bool kept = false;
        for (; lanes; lanes &= lanes - 1u) {
          const std::size_t i = std::size_t(std::countr_zero(lanes));
          if constexpr (Count) counters->prims_tested++;
          kept |= leaf_fn(base + i, bvh.prim_ids_[j], rays[i]);
        }
        return kept;
      };
      PacketBatch t_hi = hi_now();
      if (bvh.leaf_boxes_.empty()) {
        for (std::uint32_t j = first; j < first + count; ++j) test(j, packet.valid);
        return;
      }
      constexpr std::uint32_t kOrdered = 16;
      if (count > kOrdered) {
        for (std::uint32_t j = first; j < first + count; ++j) test(j, bvh.leaf_boxes_.enter_packet(j, packet, t_hi));
        return;
      }
      std::uint32_t order[kOrdered], lanes[kOrdered];
      float key[kOrdered];
      int k = 0;
      for (std::uint32_t j = first; j < first + count; ++j) {
        float near;
        const std::uint32_t in = bvh.leaf_boxes_.enter_packet(j, packet, t_hi, &near);
        if (!in) continue;
        int at = k++;  // insertion sort, nearest first
        for (; at > 0 && key[at - 1] > near; --at) key[at] = key[at - 1], order[at] = order[at - 1], lanes[at] = lanes[at - 1];
        key[at] = near, order[at] = j, lanes[at] = in;
      }
      bool shortened = false;  // some ray's hit moved closer since the boxes were tested
      for (int m = 0; m < k; ++m) {
        if (test(order[m], shortened ? bvh.leaf_boxes_.enter_packet(order[m], packet, t_hi) : lanes[m])) {
          t_hi = hi_now();
          shortened = true;
        }
      }
    }
  };

  /// The closest-hit walk, for one ray or a frustum of rays (Query): children front to back by
  /// entry distance, the nearest taken, the rest pushed farthest first with their distance;
  /// popped entries starting beyond the current t_hi are skipped; leaves tested when taken.
  template <bool Count, class Query>
  void closest(Query& q, TraversalCounters* counters) const {
    const float t_lo = q.t_lo();
    float t_hi = q.t_hi();
    Entry stack[kStackSize];
    int sp = 0;
    std::uint32_t node = 0;
    alignas(64) float tn[W];
    for (;;) {
      if constexpr (Count) {
        counters->nodes_visited += q.rays();
        counters->boxes_tested += W * q.rays();
      }
      const Node& n = nodes_[node];
      // In an 8-wide node the children's indices fill the last cache line, which the box test
      // does not read: ask for it now, so that it arrives while the boxes are tested rather than
      // after (spheres8000's camera rays took about 7% less time, docs/meshes.md). In a 4-wide
      // node the box test reads that line anyway.
      __builtin_prefetch(n.child);
      std::uint32_t bits = q.enter(n, t_lo, t_hi, tn);
      if (bits) {
        // Push every entered child but the nearest, farthest first; then take the nearest. A
        // leaf taken is tested at once.
        Entry near{0, 0, kInfinity, 0};
        const std::uint32_t box = node * std::uint32_t(W);
        const int first = std::countr_zero(bits);
        const std::uint32_t rest = bits & (bits - 1u);
        if (rest == 0) {
          near = {n.child[first], n.count[first], tn[first], box + std::uint32_t(first)};
        } else if (std::has_single_bit(rest)) {
          // Two children, the common case: push the farther and take the nearer (the later
          // one at a tie, as the sort below would).
          const int second = std::countr_zero(rest);
          const Entry a{n.child[first], n.count[first], tn[first], box + std::uint32_t(first)};
          const Entry b{n.child[second], n.count[second], tn[second], box + std::uint32_t(second)};
          const bool b_nearer = b.t <= a.t;
          stack[sp++] = b_nearer ? a : b;
          near = b_nearer ? b : a;
        } else {
          Entry hits[W];
          int k = 0;
          do {
            const int i = std::countr_zero(bits);
            bits &= bits - 1u;
            Entry e{n.child[i], n.count[i], tn[i], box + std::uint32_t(i)};
            int j = k++;  // insertion sort, nearest last
            for (; j > 0 && hits[j - 1].t < e.t; --j) hits[j] = hits[j - 1];
            hits[j] = e;
          } while (bits);
          for (int j = 0; j < k - 1; ++j) stack[sp++] = hits[j];
          near = hits[k - 1];
        }
        if (near.count == 0) {
          node = near.child;
          continue;
        }
        q.leaf(near.child, near.count, near.box);
        t_hi = q.t_hi();
      }
      // Pop the nearest pending child that still starts before the current hit; leaves are
      // tested as they come off the stack.
      for (;;) {
        if (sp == 0) return;
        const Entry e = stack[--sp];
        if (e.t > t_hi) continue;
        if (e.count == 0) {
          node = e.child;
          break;
        }
        q.leaf(e.child, e.count, e.box);
        t_hi = q.t_hi();
      }
    }
  }

  template <bool Count, class LeafFn>
  bool any_hit(Ray& ray, const NodeRay& r, LeafFn& leaf_fn, TraversalCounters* counters) const {
    const float t_lo = widen_down(ray.tmin);
    const float t_hi = widen_up(ray.tmax);
    const WatertightRay tri_ray = triangles_.empty() ? WatertightRay() : WatertightRay(ray);
    std::uint32_t stack[kStackSize];
    int sp = 0;
    bool hit = false;
    std::uint32_t node = 0;
    alignas(64) float tn[W];
    for (;;) {
      if constexpr (Count) {
        counters->nodes_visited++;
        counters->boxes_tested += W;
      }
      const Node& n = nodes_[node];
      __builtin_prefetch(n.child);  // as in closest()
      std::uint32_t bits = enter(n, r, t_lo, t_hi, tn);
      while (bits) {
        const int i = std::countr_zero(bits);
        bits &= bits - 1u;
        if (n.count[i] == 0) {
          stack[sp++] = n.child[i];
        } else if (leaf_loop<Count, true>(ray, r, tri_ray, n.child[i], n.count[i], leaf_fn, counters, hit)) {
          return true;
        }
      }
      if (sp == 0) return false;
      node = stack[--sp];
    }
  }

  /// The rays of `p` (lanes) that enter child `c` of `n` within [t_lo, t_hi] of each: lane by
  /// lane the operations of enter() for that ray and that child, so the same rays enter.
  static std::uint32_t enter_rays(const Node& n, int c, const RayPacket<PacketBatch>& p, const PacketBatch& t_hi) {
    const float lo[3] = {n.planes[0][c], n.planes[2][c], n.planes[4][c]};
    const float hi[3] = {n.planes[1][c], n.planes[3][c], n.planes[5][c]};
    PacketBatch t0, t1;
    box_interval(p, lo, hi, t_hi, t0, t1);
    return simd::mask_bits<PacketBatch>(t0 <= t1) & p.valid;
  }

  /// any_hit for the rays of `packet` together: each node tests its children against every ray
  /// still open (SIMD over the rays), and a child is taken with the rays that enter it, so each
  /// ray meets the nodes and primitives its own walk would. Returns the rays some primitive
  /// occludes; stops when every ray is.
  template <bool Count, class LeafFn>
  std::uint32_t any_hit_packet(std::span<Ray> group, const RayPacket<PacketBatch>& packet, std::size_t lane_base,
                               LeafFn& leaf_fn, TraversalCounters* counters) const {
    alignas(64) float hi[kPacket];
    for (std::size_t i = 0; i < kPacket; ++i) hi[i] = widen_up(group[i < group.size() ? i : 0].tmax);
    const PacketBatch t_hi = PacketBatch::load_aligned(hi);
    struct Pending {
      std::uint32_t node;
      std::uint32_t lanes;  ///< The rays that entered it.
    };
    Pending stack[kStackSize];
    int sp = 0;
    std::uint32_t live = packet.valid;  // rays not yet occluded
    Pending at{0, live};
    // Where the rays' directions share their signs (a tile's shadow rays toward one light), the
    // group's frustum tests a node's children in one step first and only the children it may
    // enter are tested ray by ray: the frustum is conservative (enter_frustum), so no ray's
    // answer changes.
    PacketFrustum frustum;
    const bool use_frustum = frustum.bound(packet, true);
    const float frustum_lo = simd::reduce_min(packet.t_lo), frustum_hi = simd::reduce_max(t_hi);
    alignas(64) float tn[W];
    for (;;) {
      at.lanes &= live;
      if (at.lanes) {
        if constexpr (Count) {
          counters->nodes_visited += std::uint64_t(std::popcount(at.lanes));
          counters->boxes_tested += std::uint64_t(W) * std::uint64_t(std::popcount(at.lanes));
        }
        const Node& n = nodes_[at.node];
        std::uint32_t children = (1u << W) - 1u;
        if (use_frustum)
          children = frustum.one_origin ? enter_frustum<true>(n, frustum, frustum_lo, frustum_hi, tn)
                                        : enter_frustum<false>(n, frustum, frustum_lo, frustum_hi, tn);
        for (; children; children &= children - 1u) {
          const int c = std::countr_zero(children);
          if (!(n.planes[0][c] <= n.planes[1][c])) continue;  // unused slot
          const std::uint32_t in = enter_rays(n, c, packet, t_hi) & at.lanes;
          if (!in) continue;
          if (n.count[c] == 0) {
            stack[sp++] = {n.child[c], in};
            continue;
          }
          if constexpr (TriangleLeafFn<LaneLeaf<LeafFn>>) {
            if (!triangles_.empty()) {
              for (std::uint32_t lanes = in & live; lanes; lanes &= lanes - 1u) {
                const std::size_t i = std::size_t(std::countr_zero(lanes));
                LaneLeaf<LeafFn> lane{&leaf_fn, lane_base + i};
                bool hit = false;
                if (triangles_.template test<Count, true>(prim_ids_.data(), n.child[c], n.count[c], group[i],
                                                          WatertightRay(group[i]), lane, counters, hit))
                  live &= ~(1u << i);
              }
              if (!live) return packet.valid;
              at.lanes &= live;
              continue;
            }
          }
          for (std::uint32_t j = n.child[c]; j < n.child[c] + n.count[c]; ++j) {
            std::uint32_t lanes = in & live;
            if (!leaf_boxes_.empty()) lanes &= leaf_boxes_.enter_packet(j, packet, t_hi);
            for (; lanes; lanes &= lanes - 1u) {
              const std::size_t i = std::size_t(std::countr_zero(lanes));
              if constexpr (Count) counters->prims_tested++;
              if (leaf_fn(lane_base + i, prim_ids_[j], group[i])) live &= ~(1u << i);
            }
          }
          if (!live) return packet.valid;
          at.lanes &= live;
        }
      }
      if (sp == 0) return packet.valid & ~live;
      at = stack[--sp];
    }
  }

  /// The tree over `boxes`, then, with `with_leaf_boxes`, the primitives' boxes beside its leaves.
  void build(std::span<const Aabb> boxes, std::uint64_t budget_bytes, bool with_leaf_boxes,
             const PrimitiveOverlap& overlap);
  /// The nodes, prim_ids_ and the tree's counts in stats_ by a spatial-split build of at most
  /// `max_refs` references (wide_bvh_spatial.cpp).
  void build_spatial(std::span<const Aabb> boxes, const PrimitiveOverlap& overlap, std::uint64_t max_refs);
  /// The leaves' ranges of prim_ids_, which SIMD leaves store their shapes by.
  std::vector<LeafRange> leaf_ranges() const {
    std::vector<LeafRange> leaves;
    leaves.reserve(stats_.leaves);
    for (const Node& n : nodes_)
      for (int i = 0; i < W; ++i)
        if (n.count[i] > 0) leaves.push_back({n.child[i], n.count[i]});
    return leaves;
  }
  std::uint64_t memory_bytes() const {
    return nodes_.size() * sizeof(Node) + prim_ids_.size() * sizeof(std::uint32_t) + spheres_.memory_bytes() +
           triangles_.memory_bytes() + leaf_boxes_.memory_bytes();
  }

  /// The leaf loop of one ray: SIMD sphere or triangle leaves where those are attached and
  /// leaf_fn takes a t (and, for triangles, names its routine; tri_ray is WatertightRay(ray),
  /// computed once per ray); else the primitives' own boxes first, several at a time, and leaf_fn for the
  /// primitives whose box the ray may enter: for any hit in leaf order, for the closest hit
  /// nearest box first, stopping at the first box that starts beyond the hit found (as the
  /// traversal skips a child entered beyond it). Which primitive wins does not depend on the
  /// order: leaf_fn keeps the nearest, ties to the lower id.
  template <bool Count, bool AnyHit, class LeafFn>
  bool leaf_loop(Ray& ray, const NodeRay& r, const WatertightRay& tri_ray, std::uint32_t first, std::uint32_t count,
                 LeafFn& leaf_fn, TraversalCounters* counters, bool& hit) const {
    if constexpr (TriangleLeafFn<LeafFn>) {
      if (!triangles_.empty())
        return triangles_.template test<Count, AnyHit>(prim_ids_.data(), first, count, ray, tri_ray, leaf_fn,
                                                       counters, hit);
    }
    const bool sphere_leaves = AcceptingLeafFn<LeafFn> && !spheres_.empty();
    if (sphere_leaves || leaf_boxes_.empty())
      return test_leaf<Count, AnyHit>(prim_ids_.data(), spheres_, first, count, ray, leaf_fn, counters, hit);
    // tmax only shortens within the leaf: hi, taken at its start, stays conservative; the
    // closest hit narrows it after each hit (widened as the traversal widens it).
    const float lo = widen_down(ray.tmin);
    float hi = widen_up(ray.tmax);
    for (std::uint32_t j = first; j < first + count; j += LeafBoxes::kLanes) {
      const std::uint32_t lanes = std::min(LeafBoxes::kLanes, first + count - j);
      const std::uint32_t mask = lanes >= 32 ? ~0u : (1u << lanes) - 1u;
      if constexpr (AnyHit) {
        std::uint32_t bits = leaf_boxes_.enter(j, r.org, r.inv_dir, r.inv_far, r.near_row, lo, hi) & mask;
        for (; bits; bits &= bits - 1u) {
          if constexpr (Count) counters->prims_tested++;
          if (leaf_fn(prim_ids_[j + std::uint32_t(std::countr_zero(bits))], ray)) return true;
        }
      } else {
        float tn[LeafBoxes::kLanes];
        std::uint32_t bits = leaf_boxes_.enter(j, r.org, r.inv_dir, r.inv_far, r.near_row, lo, hi, tn) & mask;
        while (bits) {
          int near = std::countr_zero(bits);
          for (std::uint32_t rest = bits & (bits - 1u); rest; rest &= rest - 1u) {
            const int i = std::countr_zero(rest);
            if (tn[i] < tn[near]) near = i;
          }
          if (tn[near] > hi) break;  // every box left starts beyond the hit
          bits &= ~(1u << near);
          if constexpr (Count) counters->prims_tested++;
          if (leaf_fn(prim_ids_[j + std::uint32_t(near)], ray)) {
            hit = true;
            hi = widen_up(ray.tmax);
          }
        }
      }
    }
    return false;
  }

  Params params_;
  std::vector<Node, CacheLineAllocator<Node>> nodes_;
  std::vector<std::uint32_t> prim_ids_;
  SphereSoA spheres_;
  TriangleSoA triangles_;
  LeafBoxes leaf_boxes_;  ///< The primitives' boxes in leaf order; cleared when spheres or triangles are attached.
  BuildStats stats_;
};

/// The 4-wide BVH (`bvh4`).
using Bvh4 = WideBvh<4>;
/// The 8-wide BVH (`bvh8`).
using Bvh8 = WideBvh<8>;

extern template class WideBvh<4>;
extern template class WideBvh<8>;

}  // namespace accel
