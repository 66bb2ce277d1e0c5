#pragma once
// Spheres stored beside a structure's primitive id array, leaf by leaf, so that a leaf's spheres
// are tested several at a time (intersect_spheres, one SIMD lane per sphere) instead of one
// leaf-function call each. A leaf over ids[first, first + count) owns floats [4 first,
// 4 (first + count)): four rows of `count` floats (the centres' x, y and z, the radii). A leaf's
// spheres are one contiguous piece of memory (16 bytes a sphere, two or three cache lines for a
// leaf of eight), where one array per coordinate touched four places: on spheres8000, 17-22%
// fewer simulated L1 misses on incoherent and shadow rays (scripts/count_trace,
// docs/benchmarks.md). Duplicated references (octree and kd-tree `leaves` placement) are
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

  /// Fills the rows of every leaf of `leaves` (disjoint ranges of `ids`, every id <
  /// spheres.size()); no spheres leave it empty.
  void build(std::span<const std::uint32_t> ids, std::span<const LeafRange> leaves,
             std::span<const SphereShape> spheres) {
    *this = {};
    if (spheres.empty()) return;
    // Padded by one batch: the last leaf's loads may run past its end (those lanes are ignored).
    data_.assign(4 * ids.size() + kLanes, 0.0f);
    for (const auto& [first, count] : leaves) {
      float* leaf = data_.data() + 4 * std::size_t(first);
      for (std::uint32_t i = 0; i < count; ++i) {
        const SphereShape& s = spheres[ids[first + i]];
        leaf[i] = s.center.x;
        leaf[count + i] = s.center.y;
        leaf[2 * count + i] = s.center.z;
        leaf[3 * count + i] = s.radius;
      }
    }
  }

  /// True when no spheres were attached (the structure then calls the leaf function per id).
  bool empty() const { return data_.empty(); }
  /// Bytes held by the rows.
  std::uint64_t memory_bytes() const { return std::uint64_t(data_.capacity()) * sizeof(float); }

  /// Tests the leaf ids[begin, begin + count) (one of the leaves it was built with) as spheres,
  /// kLanes at a time, then calls leaf_fn.accept(id, t, ray) in id order for each sphere hit
  /// (finite t) within ray.tmax. Returns true when AnyHit and one was accepted; sets `hit` when
  /// one was accepted.
  template <bool Count, bool AnyHit, class LeafFn>
  bool test(const std::uint32_t* ids, std::uint32_t begin, std::uint32_t count, Ray& ray, LeafFn& leaf_fn,
            TraversalCounters* counters, bool& hit) const {
    if constexpr (Count) counters->prims_tested += count;
    const float* leaf = data_.data() + 4 * std::size_t(begin);
    for (std::uint32_t j = 0; j < count; j += kLanes) {
      const float* c = leaf + j;
      const Batch t = intersect_spheres(Batch::load_unaligned(c), Batch::load_unaligned(c + count),
                                        Batch::load_unaligned(c + 2 * count), Batch::load_unaligned(c + 3 * count), ray);
      if (accept_lanes<AnyHit>(t, std::min(kLanes, count - j), ids, begin + j, ray, leaf_fn, hit)) return true;
    }
    return false;
  }

  /// The packet form of test(): each sphere of the leaf ids[begin, begin + count) against the
  /// rays of `packet` in the lanes of `lanes`, one SIMD step per sphere; accept(lane_base + lane,
  /// id, t, rays[lane]) for each finite hit, in id order per ray (closest hit only).
  template <bool Count, class Batch, class LeafFn>
  void test_packet(const std::uint32_t* ids, std::uint32_t begin, std::uint32_t count, std::uint32_t lanes,
                   const RayPacket<Batch>& packet, std::span<Ray> rays, std::size_t lane_base, LeafFn& leaf_fn,
                   TraversalCounters* counters) const {
    if constexpr (Count) counters->prims_tested += std::uint64_t(count) * std::uint64_t(std::popcount(lanes));
    const float* leaf = data_.data() + 4 * std::size_t(begin);
    for (std::uint32_t at = begin; at < begin + count; ++at) {
      const float* c = leaf + (at - begin);
      const Batch t = sphere_root_lanes(packet.org[0], packet.org[1], packet.org[2], packet.dir[0], packet.dir[1],
                                        packet.dir[2], packet.dir_dot, packet.tmin, Batch(c[0]), Batch(c[count]),
                                        Batch(c[2 * count]), Batch(c[3 * count]));
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
  std::vector<float, CacheLineAllocator<float>> data_;
};

/// A structure's attach_spheres (attach_leaf_shapes, simd_leaves.h): the spheres of its id array
/// `ids`, stored by its leaves' ranges of it (every range a leaf function may be called on).
inline void attach_sphere_leaves(const char* structure, std::span<const std::uint32_t> ids,
                                 std::span<const LeafRange> leaves, std::span<const SphereShape> spheres,
                                 SphereSoA& soa, BuildStats& stats) {
  attach_leaf_shapes(structure, "spheres", spheres, soa, stats,
                     [&](SphereSoA& s) { s.build(ids, leaves, spheres); });
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
