#pragma once
// The primitives' own boxes stored beside a structure's primitive id array, in leaf order,
// structure-of-arrays and padded outward like node boxes, so that a leaf of a scene whose
// primitives have no SIMD test (polygons, cylinders, cones) tests the ray against its
// primitives' boxes several at a time and calls the leaf function only for those the ray may
// enter. Embree does the same with the primitive boxes of its user geometry. The box test is the
// wide nodes' (same padding, same widened interval), so it never culls a primitive the ray hits.

#include "cache_line_allocator.h"
#include "geometry.h"
#include "interval_slack.h"
#include "ray_packet.h"
#include "simd.h"

#include <cstdint>
#include <span>
#include <vector>

namespace accel {

class LeafBoxes {
 public:
  using Batch = simd::FloatLeaf;
  static constexpr std::uint32_t kLanes = std::uint32_t(Batch::size);

  /// Fills the planes for `ids` (entry j: the box of ids[j], padded by box_pad).
  void build(std::span<const std::uint32_t> ids, std::span<const Aabb> boxes);
  void clear() {
    for (auto& p : planes_) p = {};
  }
  bool empty() const { return planes_[0].empty(); }
  std::uint64_t memory_bytes() const { return 6 * std::uint64_t(planes_[0].capacity()) * sizeof(float); }

  /// Bit i set when the ray may enter box at + i within [t_lo, t_hi] (i < kLanes): each lane
  /// performs the wide node test's operations. `near_row[a]` is the plane row nearest the ray
  /// on axis a (2 a, or 2 a + 1 when the ray goes down), `inv_far` = inv_dir * kSlabFarScale.
  /// When `tn` is given, tn[i] receives lane i's entry distance (a lower bound of the distance
  /// to anything in box at + i).
  std::uint32_t enter(std::uint32_t at, const float* org, const float* inv_dir, const float* inv_far,
                      const int* near_row, float t_lo, float t_hi, float* tn = nullptr) const {
    Batch t0(t_lo), t1(t_hi);
    for (int a = 0; a < 3; ++a) {
      const Batch o(org[a]);
      const Batch t_near = (Batch::load_unaligned(planes_[near_row[a]].data() + at) - o) * Batch(inv_dir[a]);
      const Batch t_far = (Batch::load_unaligned(planes_[near_row[a] ^ 1].data() + at) - o) * Batch(inv_far[a]);
      t0 = simd::max_or_second(t_near, t0);
      t1 = simd::min_or_second(t_far, t1);
    }
    if (tn) t0.store_unaligned(tn);
    return simd::mask_bits<Batch>(t0 <= t1);
  }

  /// Bit i set when ray i of `p` may enter box j within [p.t_lo, t_hi], lane by lane the
  /// single-ray test's operations. When `nearest` is given it receives the least entry distance
  /// of the rays that may enter (+inf when none).
  template <class B>
  std::uint32_t enter_packet(std::uint32_t j, const RayPacket<B>& p, const B& t_hi, float* nearest = nullptr) const {
    const float lo[3] = {planes_[0][j], planes_[2][j], planes_[4][j]};
    const float hi[3] = {planes_[1][j], planes_[3][j], planes_[5][j]};
    B t0, t1;
    box_interval(p, lo, hi, t_hi, t0, t1);
    const auto entered = t0 <= t1;
    // Lanes past the packet's rays repeat its first ray, so they do not change the least.
    if (nearest) *nearest = simd::reduce_min(xsimd::select(entered, t0, B(kInfinity)));
    return simd::mask_bits<B>(entered) & p.valid;
  }

 private:
  std::vector<float, CacheLineAllocator<float>> planes_[6];  ///< lo x, hi x, lo y, hi y, lo z, hi z.
};

}  // namespace accel
