#pragma once
// Triangles stored beside a structure's primitive id array, leaf by leaf, so that a leaf's
// triangles are tested several at a time (triangle_hit.h, one SIMD lane per triangle) by the
// routine the leaf function runs, watertight or Moller-Trumbore, instead of one leaf-function
// call each. A leaf over ids[first, first + count) owns floats [9 first, 9 (first + count)):
// nine rows of `count` floats, one row per vertex coordinate (vertex v, axis a: row 3 v + a).
// A leaf's triangles are one contiguous piece of memory (36 bytes a triangle, three to five
// cache lines for a leaf of eight), where one array per coordinate would touch nine places.

#include "cache_line_allocator.h"
#include "geometry.h"
#include "simd.h"
#include "simd_leaves.h"
#include "stats.h"
#include "triangle_hit.h"
#include "triangle_shape.h"

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace accel {

class TriangleSoA {
 public:
  using Batch = simd::FloatLeaf;
  /// Triangles tested per SIMD step.
  static constexpr std::uint32_t kLanes = std::uint32_t(Batch::size);

  /// Fills the rows of every leaf of `leaves` (disjoint ranges of `ids`, every id <
  /// triangles.size()); no triangles leave it empty. Runs in parallel loops (triangle_soa.cpp),
  /// within the caller's TBB arena.
  void build(std::span<const std::uint32_t> ids, std::span<const LeafRange> leaves,
             std::span<const TriangleShape> triangles);

  /// True when no triangles were attached (the structure then calls the leaf function per id).
  bool empty() const { return data_.empty(); }
  /// Bytes held by the rows.
  std::uint64_t memory_bytes() const { return std::uint64_t(data_.capacity()) * sizeof(float); }

  /// Tests the leaf ids[begin, begin + count) (one of the leaves it was built with) as triangles
  /// by leaf_fn.triangle_test(), kLanes at a time, then calls leaf_fn.accept(id, t, ray) in id
  /// order for each hit within ray.tmax. `w` is WatertightRay(ray), computed once per ray by the
  /// caller. Returns true when AnyHit and one was accepted; sets `hit` when one was accepted.
  template <bool Count, bool AnyHit, class LeafFn>
  bool test(const std::uint32_t* ids, std::uint32_t begin, std::uint32_t count, Ray& ray, const WatertightRay& w,
            LeafFn& leaf_fn, TraversalCounters* counters, bool& hit) const {
    if constexpr (Count) counters->prims_tested += count;
    const float* leaf = data_.data() + 9 * std::size_t(begin);
    if (leaf_fn.triangle_test() == TriangleTest::Moller) {
      constexpr int kWorld[3] = {0, 1, 2};
      for (std::uint32_t j = 0; j < count; j += kLanes) {
        const Batch t = moller_lanes(load(leaf, count, j, kWorld), ray);
        if (accept_lanes<AnyHit>(t, std::min(kLanes, count - j), ids, begin + j, ray, leaf_fn, hit)) return true;
      }
      return false;
    }
    // The watertight routine works on the ray's permuted axes: load the rows in that order.
    const int axes[3] = {w.kx, w.ky, w.kz};
    for (std::uint32_t j = 0; j < count; j += kLanes) {
      const std::uint32_t lanes = std::min(kLanes, count - j);
      const Batch t = watertight_lanes_permuted(load(leaf, count, j, axes), ray, w, (1u << lanes) - 1u);
      if (accept_lanes<AnyHit>(t, lanes, ids, begin + j, ray, leaf_fn, hit)) return true;
    }
    return false;
  }

 private:
  /// Lanes j.. of a leaf's rows, axis a of the result taken from row axes[a]. Lanes past the
  /// leaf's count read the next row (or the padding after the last leaf) and are ignored.
  [[gnu::always_inline]] static TriangleLanes<Batch> load(const float* leaf, std::uint32_t count, std::uint32_t j,
                                                          const int (&axes)[3]) {
    TriangleLanes<Batch> tri;
    for (int v = 0; v < 3; ++v)
      for (int a = 0; a < 3; ++a)
        tri.p[v][a] = Batch::load_unaligned(leaf + std::size_t(3 * v + axes[a]) * count + j);
    return tri;
  }

  std::vector<float, CacheLineAllocator<float>> data_;  ///< The leaves' rows, then kLanes floats of padding.
};

}  // namespace accel
