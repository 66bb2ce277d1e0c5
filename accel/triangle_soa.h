#pragma once
// Triangles stored structure-of-arrays beside a structure's primitive id array, so that a leaf's
// triangles are tested several at a time (triangle_hit.h, one SIMD lane per triangle) by the
// routine the leaf function runs, watertight or Moller-Trumbore, instead of one leaf-function
// call each. Entry j holds the triangle of ids[j]: nine arrays, one per vertex coordinate.

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

  /// Fills the arrays for `ids` (every id < triangles.size()); no triangles leave it empty. Runs
  /// in parallel loops (triangle_soa.cpp), within the caller's TBB arena.
  void build(std::span<const std::uint32_t> ids, std::span<const TriangleShape> triangles);

  /// True when no triangles were attached (the structure then calls the leaf function per id).
  bool empty() const { return coords_[0].empty(); }
  /// Bytes held by the nine arrays.
  std::uint64_t memory_bytes() const { return 9 * std::uint64_t(coords_[0].capacity()) * sizeof(float); }

  /// Tests ids[begin, begin + count) as triangles by leaf_fn.triangle_test(), kLanes at a time,
  /// then calls leaf_fn.accept(id, t, ray) in id order for each hit within ray.tmax. `w` is
  /// WatertightRay(ray), computed once per ray by the caller. Returns true when AnyHit and one
  /// was accepted; sets `hit` when one was accepted.
  template <bool Count, bool AnyHit, class LeafFn>
  bool test(const std::uint32_t* ids, std::uint32_t begin, std::uint32_t count, Ray& ray, const WatertightRay& w,
            LeafFn& leaf_fn, TraversalCounters* counters, bool& hit) const {
    if constexpr (Count) counters->prims_tested += count;
    if (leaf_fn.triangle_test() == TriangleTest::Moller) {
      for (std::uint32_t j = 0; j < count; j += kLanes) {
        const Batch t = moller_lanes(load(begin + j), ray);
        if (accept_lanes<AnyHit>(t, std::min(kLanes, count - j), ids, begin + j, ray, leaf_fn, hit)) return true;
      }
      return false;
    }
    for (std::uint32_t j = 0; j < count; j += kLanes) {
      const std::uint32_t lanes = std::min(kLanes, count - j);
      const Batch t = watertight_lanes(load(begin + j), ray, w, (1u << lanes) - 1u);
      if (accept_lanes<AnyHit>(t, lanes, ids, begin + j, ray, leaf_fn, hit)) return true;
    }
    return false;
  }

 private:
  [[gnu::always_inline]] TriangleLanes<Batch> load(std::uint32_t at) const {
    TriangleLanes<Batch> tri;
    for (int v = 0; v < 3; ++v)
      for (int a = 0; a < 3; ++a) tri.p[v][a] = Batch::load_unaligned(coords_[3 * v + a].data() + at);
    return tri;
  }

  std::vector<float, CacheLineAllocator<float>> coords_[9];  ///< coords_[3 v + a][j]: vertex v, axis a.
};

}  // namespace accel
