#pragma once
// What the SIMD leaves of every shape share (spheres: sphere_soa.h; triangles: triangle_soa.h):
// the leaf functions that can take a t computed elsewhere, the loop that hands a batch's hits to
// such a leaf function, and the step that attaches a structure's shapes beside its id array.

#include "geometry.h"
#include "simd.h"
#include "stats.h"
#include "triangle_shape.h"

#include <algorithm>
#include <chrono>
#include <concepts>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>

namespace accel {

/// A leaf's range of a structure's id array, ids[first, first + count): what the SIMD leaves
/// (SphereSoA, TriangleSoA) store their shapes by, one contiguous piece per leaf.
struct LeafRange {
  std::uint32_t first = 0, count = 0;
};

/// A leaf function that can take a t computed elsewhere: accept(id, t, ray) must do exactly
/// what leaf_fn(id, ray) does when leaf_fn's own test of `id` gives t. The tracer's leaf
/// functions provide it; with it a structure holding SphereSoA tests spheres in SIMD. A
/// structure skips accept for a t above ray.tmax, which the contract never accepts.
template <class LeafFn>
concept AcceptingLeafFn = requires(LeafFn& f, std::uint32_t id, float t, Ray& ray) {
  { f.accept(id, t, ray) } -> std::convertible_to<bool>;
};

/// An accepting leaf function that also says which ray/triangle routine its own test runs, so
/// that a structure holding TriangleSoA runs the same routine in SIMD.
template <class LeafFn>
concept TriangleLeafFn = AcceptingLeafFn<LeafFn> && requires(const LeafFn& f) {
  { f.triangle_test() } -> std::same_as<TriangleTest>;
};

/// Hands the hits among the first `lanes` lanes of `t` (one lane per entry of ids[at, at +
/// lanes)) to leaf_fn.accept in id order: those within ray.tmax, never a miss (+inf), even while
/// tmax is +inf. Returns true when AnyHit and one was accepted; sets `hit` when one was accepted.
template <bool AnyHit, class Batch, class LeafFn>
[[gnu::always_inline]] inline bool accept_lanes(const Batch& t, std::uint32_t lanes, const std::uint32_t* ids,
                                                std::uint32_t at, Ray& ray, LeafFn& leaf_fn, bool& hit) {
  const float limit = std::min(ray.tmax, std::numeric_limits<float>::max());
  std::uint32_t bits = simd::mask_bits<Batch>(t <= Batch(limit)) & ((1u << lanes) - 1u);
  if (!bits) return false;
  alignas(64) float ts[Batch::size];
  t.store_aligned(ts);
  do {
    const int i = simd::first_lane(bits);
    bits &= bits - 1u;
    if (leaf_fn.accept(ids[at + std::uint32_t(i)], ts[i], ray)) {
      if constexpr (AnyHit) return true;
      hit = true;
    }
  } while (bits);
  return false;
}

/// A structure's attach step for SIMD leaves of one shape: checks that `shapes` holds one shape
/// per primitive the structure was built over, fills `soa` by fill(soa), and adds the time it
/// takes and the bytes it holds to `stats`.
template <class SoA, class Shape, class Fill>
void attach_leaf_shapes(const char* structure, const char* what, std::span<const Shape> shapes, SoA& soa,
                        BuildStats& stats, Fill&& fill) {
  if (shapes.size() != stats.primitives)
    throw std::invalid_argument(std::string(structure) + ": " + std::to_string(shapes.size()) + " " + what +
                                " attached to a structure over " + std::to_string(stats.primitives) +
                                " primitives");
  const auto start = std::chrono::steady_clock::now();
  stats.memory_bytes -= soa.memory_bytes();
  fill(soa);
  stats.memory_bytes += soa.memory_bytes();
  stats.build_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace accel
