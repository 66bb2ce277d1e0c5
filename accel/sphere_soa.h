#pragma once
// Spheres stored structure-of-arrays beside a structure's primitive id array, so that a leaf's
// spheres are tested several at a time (intersect_spheres, one SIMD lane per sphere) instead
// of one leaf-function call each. Entry j holds the sphere of ids[j]; a leaf's range of ids is
// the same range here. Duplicated references (octree and kd-tree `leaves` placement) are
// duplicated here too.

#include "cache_line_allocator.h"
#include "geometry.h"
#include "leaf_loop.h"
#include "ray_packet.h"
#include "simd_leaves.h"
#include "simd.h"
#include "sphere_hit.h"
#include "stats.h"

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace accel {

class SphereSoA {
 public:
  using Batch = simd::FloatLeaf;
  /// Spheres tested per SIMD step.
  static constexpr std::uint32_t kLanes = std::uint32_t(Batch::size);

  /// Fills the arrays for `ids` (every id < spheres.size()); empty spheres leave it empty.
  void build(std::span<const std::uint32_t> ids, std::span<const SphereShape> spheres) {
    *this = {};
    if (spheres.empty()) return;
    // Padded by one batch: a leaf's last load may run past its end (those lanes are ignored).
    const std::size_t n = ids.size() + kLanes;
    cx_.assign(n, 0.0f);
    cy_.assign(n, 0.0f);
    cz_.assign(n, 0.0f);
    r_.assign(n, 0.0f);
    for (std::size_t j = 0; j < ids.size(); ++j) {
      const SphereShape& s = spheres[ids[j]];
      cx_[j] = s.center.x;
      cy_[j] = s.center.y;
      cz_[j] = s.center.z;
      r_[j] = s.radius;
    }
  }

  /// True when no spheres were attached (the structure then calls the leaf function per id).
  bool empty() const { return cx_.empty(); }
  /// Bytes held by the four arrays.
  std::uint64_t memory_bytes() const { return 4 * std::uint64_t(cx_.capacity()) * sizeof(float); }

  /// Tests ids[begin, begin + count) as spheres, kLanes at a time, then calls
  /// leaf_fn.accept(id, t, ray) in id order for each sphere hit (finite t) within ray.tmax. Returns true
  /// when AnyHit and one was accepted; sets `hit` when one was accepted.
  template <bool Count, bool AnyHit, class LeafFn>
  bool test(const std::uint32_t* ids, std::uint32_t begin, std::uint32_t count, Ray& ray, LeafFn& leaf_fn,
            TraversalCounters* counters, bool& hit) const {
    if constexpr (Count) counters->prims_tested += count;
    for (std::uint32_t j = 0; j < count; j += kLanes) {
      const std::uint32_t at = begin + j;
      const Batch t = intersect_spheres(Batch::load_unaligned(cx_.data() + at), Batch::load_unaligned(cy_.data() + at),
                                        Batch::load_unaligned(cz_.data() + at), Batch::load_unaligned(r_.data() + at),
                                        ray);
      if (accept_lanes<AnyHit>(t, std::min(kLanes, count - j), ids, at, ray, leaf_fn, hit)) return true;
    }
    return false;
  }

  /// The packet form of test(): each sphere of ids[begin, begin + count) against the rays of
  /// `packet` in the lanes of `lanes`, one SIMD step per sphere; accept(lane_base + lane, id, t,
  /// rays[lane]) for each finite hit, in id order per ray (closest hit only).
  template <bool Count, class Batch, class LeafFn>
  void test_packet(const std::uint32_t* ids, std::uint32_t begin, std::uint32_t count, std::uint32_t lanes,
                   const RayPacket<Batch>& packet, std::span<Ray> rays, std::size_t lane_base, LeafFn& leaf_fn,
                   TraversalCounters* counters) const {
    if constexpr (Count) counters->prims_tested += std::uint64_t(count) * std::uint64_t(std::popcount(lanes));
    for (std::uint32_t at = begin; at < begin + count; ++at) {
      const Batch t = sphere_root_lanes(packet.org[0], packet.org[1], packet.org[2], packet.dir[0], packet.dir[1],
                                        packet.dir[2], packet.dir_dot, packet.tmin, Batch(cx_[at]), Batch(cy_[at]),
                                        Batch(cz_[at]), Batch(r_[at]));
      std::uint32_t bits = simd::mask_bits<Batch>(t < Batch(kInfinity)) & lanes;
      if (!bits) continue;
      alignas(64) float ts[Batch::size];
      t.store_aligned(ts);
      do {
        const int i = simd::first_lane(bits);
        bits &= bits - 1u;
        leaf_fn.accept(lane_base + std::size_t(i), ids[at], ts[i], rays[std::size_t(i)]);
      } while (bits);
    }
  }

 private:
  std::vector<float, CacheLineAllocator<float>> cx_, cy_, cz_, r_;
};

/// A structure's attach_spheres (attach_leaf_shapes, simd_leaves.h).
inline void attach_sphere_leaves(const char* structure, std::span<const std::uint32_t> ids,
                                 std::span<const SphereShape> spheres, SphereSoA& soa, BuildStats& stats) {
  attach_leaf_shapes(structure, "spheres", ids, spheres, soa, stats);
}

/// The leaf loop of a structure that may hold SphereSoA: ids[begin, begin + count) tested as
/// spheres in SIMD when `spheres` is filled and leaf_fn accepts a precomputed t, else one
/// leaf_fn call per id (test_leaf in leaf_loop.h). Same result either way.
template <bool Count, bool AnyHit, class LeafFn>
inline bool test_leaf(const std::uint32_t* ids, const SphereSoA& spheres, std::uint32_t begin, std::uint32_t count,
                      Ray& ray, LeafFn& leaf_fn, TraversalCounters* counters, bool& hit) {
  if constexpr (AcceptingLeafFn<LeafFn>) {
    if (!spheres.empty()) return spheres.template test<Count, AnyHit>(ids, begin, count, ray, leaf_fn, counters, hit);
  }
  return test_leaf<Count, AnyHit>(ids + begin, count, ray, leaf_fn, counters, hit);
}

}  // namespace accel
