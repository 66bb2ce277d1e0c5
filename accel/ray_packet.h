#pragma once
// A packet of rays for coherent queries (camera rays over a tile of pixels): up to Batch::size
// rays, one per SIMD lane, structure-of-arrays, with what the slab test and the sphere test need
// of each, computed lane by lane with the single-ray operations (RaySetup, sphere_root), so each
// lane holds the bits the single-ray query would compute.
//
// The packet leaf function of the traversal contract takes the ray's index in the packet:
// leaf_fn(lane, id, ray), and, where it can take a t computed elsewhere, accept(lane, id, t, ray).

#include "geometry.h"
#include "interval_slack.h"
#include "ray_setup.h"
#include "simd.h"

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>

namespace accel {

/// A packet leaf function that can take a t computed elsewhere (SIMD sphere and triangle leaves): the
/// packet form of AcceptingLeafFn (simd_leaves.h).
template <class LeafFn>
concept AcceptingPacketLeafFn = requires(LeafFn& f, std::size_t lane, std::uint32_t id, float t, Ray& ray) {
  { f.accept(lane, id, t, ray) } -> std::convertible_to<bool>;
};

template <class Batch>
struct RayPacket {
  static constexpr std::size_t kLanes = Batch::size;
  using Mask = typename Batch::batch_bool_type;

  Batch org[3];       ///< Origins.
  Batch dir[3];       ///< Directions.
  Batch dir_dot;      ///< dot(dir, dir), as sphere_root computes it.
  Batch tmin;         ///< Interval starts, as the primitive tests take them.
  Batch t_lo;         ///< widen_down(tmin): the interval start the box tests take.
  Batch inv_dir[3];   ///< RaySetup's 1 / dir (+-inf for a +-0 component).
  Batch inv_far[3];   ///< inv_dir * kSlabFarScale, for far slab distances.
  Mask neg[3];        ///< Lanes whose direction component has its sign bit set (RaySetup::neg).
  std::uint32_t valid = 0;  ///< Bit i set when lane i holds a ray.

  RayPacket() = default;  ///< Uninitialised; to be assigned or constructed over.
  /// Loads rays[0, n) with 0 < n <= kLanes; lanes past n repeat ray 0 and are not valid.
  explicit RayPacket(std::span<const Ray> rays) {
    alignas(64) float f[7][kLanes];
    for (std::size_t i = 0; i < kLanes; ++i) {
      const Ray& ray = rays[i < rays.size() ? i : 0];
      for (int a = 0; a < 3; ++a) {
        f[a][i] = ray.org[a];
        f[3 + a][i] = ray.dir[a];
      }
      f[6][i] = ray.tmin;
    }
    for (int a = 0; a < 3; ++a) {
      org[a] = Batch::load_aligned(f[a]);
      dir[a] = Batch::load_aligned(f[3 + a]);
      inv_dir[a] = Batch(1.0f) / dir[a];  // IEEE division: RaySetup's scalar 1 / dir, lane by lane
      inv_far[a] = inv_dir[a] * Batch(kSlabFarScale);
      neg[a] = inv_dir[a] < Batch(0.0f);  // 1 / -0 = -inf: the sign bit, -0 included
    }
    dir_dot = (dir[0] * dir[0] + dir[1] * dir[1]) + dir[2] * dir[2];
    tmin = Batch::load_aligned(f[6]);
    t_lo = tmin - xsimd::abs(tmin) * Batch(kIntervalSlack);  // widen_down, lane by lane
    valid = (1u << rays.size()) - 1u;  // kLanes <= 16
  }
};

/// The interval in which each ray of `p` crosses the box [lo, hi] (per axis), clipped to
/// [p.t_lo, t_hi]: lane by lane the single-ray slab test's operations (the near plane by the
/// direction's sign, far distances through inv_far). A lane's ray enters the box when t0 <= t1.
template <class Batch>
void box_interval(const RayPacket<Batch>& p, const float lo[3], const float hi[3], const Batch& t_hi, Batch& t0,
                  Batch& t1) {
  t0 = p.t_lo;
  t1 = t_hi;
  for (int a = 0; a < 3; ++a) {
    const Batch l(lo[a]), h(hi[a]);
    const Batch t_near = (xsimd::select(p.neg[a], h, l) - p.org[a]) * p.inv_dir[a];
    const Batch t_far = (xsimd::select(p.neg[a], l, h) - p.org[a]) * p.inv_far[a];
    t0 = simd::max_or_second(t_near, t0);
    t1 = simd::min_or_second(t_far, t1);
  }
}

}  // namespace accel
