#pragma once
// The paper's octree (section 3.1): the root cell is a cube around the scene; a cell holding more
// than max_leaf_size primitives, above max_depth, splits into 8 equal children. Empty children
// are neither stored nor visited. Built in octree_builder.cpp; traversed front to back here.

#include "geometry.h"
#include "primitive_overlap.h"
#include "interval_slack.h"
#include "knobs/knob_table.h"
#include "leaf_loop.h"
#include "placement.h"
#include "ray_setup.h"
#include "sphere_soa.h"
#include "stats.h"

#include <nlohmann/json.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace accel {

struct BuildLimits;

/// Knobs of the octree. The defaults suit the paper's 8000-sphere scene: a sphere test costs
/// less than a cell step, and leaves of 8 traced faster there than leaves of 1, 2 or 4 (the
/// tuner refines this per scene); depth 8 (cells 1/256 of the scene) is not reached there, so
/// it only guards against runaway subdivision.
struct OctreeParams {
  /// Deepest level a cell may be split to, root = 0; a cell at this depth is a leaf.
  int max_depth = 8;
  /// A cell holding more primitives than this is split (unless max_depth stops it).
  int max_leaf_size = 8;
  /// Where a primitive overlapping several children is stored.
  Placement placement = Placement::Leaves;

  /// Name, range, unit and doc line of every knob above.
  static const knobs::KnobTable<OctreeParams>& knobs();
};

/// One stored cell. Its geometry is implicit: child c of a cell is the octant whose bit k is 1
/// when it is the upper half on axis k. The stored children of a cell are contiguous, in
/// increasing c, so child c sits at first_child + (number of stored children below c).
struct OctreeNode {
  std::uint32_t first_child = 0;  ///< Index of the first stored child (when child_mask != 0).
  std::uint32_t prim_begin = 0;   ///< First entry of this cell's primitives in the id array.
  std::uint32_t prim_count = 0;   ///< Primitives stored at this cell: a leaf's, or with
                                  ///< every_level the ones straddling an inner cell's children.
  std::uint8_t child_mask = 0;    ///< Bit c set when child c is stored; 0 for a leaf.
  std::uint8_t pad[3] = {};       ///< Keeps the node at 16 bytes.

  bool is_leaf() const { return child_mask == 0; }
};
static_assert(sizeof(OctreeNode) == 16, "four octree nodes per cache line");

/// Midpoint of a cell, the three planes its children share. The builder and the traversal both
/// use this one expression, so they agree on every plane to the bit.
inline Vec3 cell_mid(const Aabb& cell) { return 0.5f * (cell.lo + cell.hi); }

/// Child c of `cell` (bit k of c: upper half on axis k), cut at `mid`.
inline Aabb child_cell(const Aabb& cell, const Vec3& mid, unsigned c) {
  Aabb out;
  for (int a = 0; a < 3; ++a) {
    const bool upper = (c >> a) & 1u;
    out.lo[a] = upper ? mid[a] : cell.lo[a];
    out.hi[a] = upper ? cell.hi[a] : mid[a];
  }
  return out;
}

class Octree {
 public:
  using Params = OctreeParams;
  static constexpr const char* kName = "octree";
  static constexpr const char* kSummary = "the paper's section 3.1 octree: 8 equal children per cell";
  /// Traversal stack entries: each level pushes at most 8 children and pops its own cell.
  static constexpr int kStackSize = 7 * 64 + 8;

  Octree() = default;
  /// Builds over `boxes` (primitive id = index). Throws knobs::ConfigError for a bad knob or when the
  /// build would pass the memory budget of `limits`.
  Octree(std::span<const Aabb> boxes, const OctreeParams& params, const BuildLimits& limits);
  explicit Octree(std::span<const Aabb> boxes, const OctreeParams& params = {});

  /// Closest hit: cells front to back, calling leaf_fn(prim_id, ray), which may shorten
  /// ray.tmax; stops once the next cell starts beyond the current hit.
  template <bool Count = false, class LeafFn>
  void intersect(Ray& ray, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    traverse<Count, false>(ray, leaf_fn, counters);
  }

  /// Any hit: stops at the first primitive whose leaf_fn returns true.
  template <bool Count = false, class LeafFn>
  bool occluded(const Ray& ray_in, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    Ray ray = ray_in;
    return traverse<Count, true>(ray, leaf_fn, counters);
  }

  /// Stores the spheres of a sphere-only scene (spheres[i] is primitive i) beside the id array,
  /// so that leaves test them in SIMD for leaf functions that accept a precomputed t
  /// (sphere_soa.h). The time it takes is added to stats().build_ms.
  void attach_spheres(std::span<const SphereShape> spheres) {
    std::vector<LeafRange> leaves;  // every cell's own primitives: a leaf's, or an inner cell's (every_level)
    for (const OctreeNode& n : nodes_)
      if (n.prim_count > 0) leaves.push_back({n.prim_begin, n.prim_count});
    attach_sphere_leaves(kName, prim_ids_, leaves, spheres, spheres_, stats_);
  }

  const OctreeParams& params() const { return params_; }
  const BuildStats& stats() const { return stats_; }
  /// The root cell: a cube around every primitive box.
  const Aabb& root_cell() const { return root_cell_; }
  /// The cells, root first.
  std::span<const OctreeNode> nodes() const { return nodes_; }
  /// Primitive ids; a cell covers [prim_begin, prim_begin + prim_count).
  std::span<const std::uint32_t> prim_ids() const { return prim_ids_; }

 private:
  // A hit whose t ties the current hit (or a cell entry within rounding of it) must still be
  // visited, because at a tie the lower id wins whatever the visiting order: cells are pruned
  // against tmax widened by a few ulps (interval_slack.h).

  /// A cell waiting on the stack with the ray's parameter interval inside it. Plain floats, not
  /// an Aabb: the stack is not initialised per ray, and its entries are copied often.
  struct Pending {
    float lo[3], hi[3];
    float t0, t1;
    std::uint32_t node;
  };

  template <bool Count, bool AnyHit, class LeafFn>
  bool traverse(Ray& ray, LeafFn& leaf_fn, TraversalCounters* counters) const {
    if constexpr (Count) counters->rays++;
    if (prim_ids_.empty()) return false;
    const RaySetup rs(ray);
    float t0 = ray.tmin, t1 = ray.tmax;
    if constexpr (Count) counters->boxes_tested++;
    if (!slab_clip(root_cell_, rs, t0, t1)) return false;

    const unsigned octant = unsigned(rs.octant());
    Pending stack[kStackSize];
    int sp = 0;
    stack[sp++] = {{root_cell_.lo.x, root_cell_.lo.y, root_cell_.lo.z},
                   {root_cell_.hi.x, root_cell_.hi.y, root_cell_.hi.z},
                   t0,
                   t1,
                   0};
    bool hit = false;
    while (sp > 0) {
      const Pending p = stack[--sp];
      if (p.t0 > widen_up(ray.tmax)) continue;
      if constexpr (Count) counters->nodes_visited++;
      const OctreeNode& n = nodes_[p.node];
      if (test_leaf<Count, AnyHit>(prim_ids_.data(), spheres_, n.prim_begin, n.prim_count, ray, leaf_fn, counters,
                                   hit))
        return true;
      if (n.is_leaf()) continue;

      // Octant-relative child index j = c ^ octant: bit k of j is 0 for the half the ray is in
      // before it crosses the mid-plane of axis k (at tm[k]) and 1 for the half after it.
      const Aabb cell{Vec3(p.lo[0], p.lo[1], p.lo[2]), Vec3(p.hi[0], p.hi[1], p.hi[2])};
      const Vec3 mid = cell_mid(cell);
      const float tm[3] = {(mid.x - rs.org.x) * rs.inv_dir.x, (mid.y - rs.org.y) * rs.inv_dir.y,
                           (mid.z - rs.org.z) * rs.inv_dir.z};
      const float t_limit = widen_up(ray.tmax);
      // Pushes child c (if stored) with the ray's interval [lo, hi] inside it.
      auto push = [&](unsigned c, float lo, float hi) {
        if constexpr (Count) counters->boxes_tested++;  // one child cell's interval computed
        const unsigned below = n.child_mask & ((1u << c) - 1u);
        if (!((n.child_mask >> c) & 1u) || lo > t_limit) return false;
        Pending& e = stack[sp++];  // child_cell(cell, mid, c), written in place
        for (int a = 0; a < 3; ++a) {
          const bool upper = (c >> a) & 1u;
          e.lo[a] = upper ? mid[a] : p.lo[a];
          e.hi[a] = upper ? p.hi[a] : mid[a];
        }
        e.t0 = lo;
        e.t1 = hi;
        e.node = n.first_child + unsigned(std::popcount(below));
        return true;
      };

      if (!(std::isnan(tm[0]) || std::isnan(tm[1]) || std::isnan(tm[2]))) {
        // The children along the ray, in order: the one holding the entry point, then one more
        // per mid-plane crossed inside [t0, t1]. Crossings exactly at t0 or t1 count, so that a
        // child the ray only touches is still visited (it may hold a tie).
        unsigned j = 0, bit[3];
        float cross[3];
        int nc = 0;
        for (int a = 0; a < 3; ++a) {
          if (tm[a] < p.t0) {
            j |= 1u << a;
          } else if (tm[a] <= p.t1) {
            int k = nc++;  // insertion keeps the crossings sorted
            for (; k > 0 && cross[k - 1] > tm[a]; --k) {
              cross[k] = cross[k - 1];
              bit[k] = bit[k - 1];
            }
            cross[k] = tm[a];
            bit[k] = 1u << a;
          }
        }
        unsigned path[4] = {j, 0, 0, 0};
        for (int k = 0; k < nc; ++k) path[k + 1] = path[k] | bit[k];
        // Farthest first, so the nearest child is on top of the stack.
        for (int k = nc; k >= 0; --k)
          push(path[k] ^ octant, k > 0 ? cross[k - 1] : p.t0, k < nc ? cross[k] : p.t1);
        continue;
      }

      // A NaN crossing (ray inside a mid-plane and parallel to it) cuts nothing: both halves get
      // the whole interval. Each stored child's interval is the cell's cut at the crossings,
      // and the children are sorted by entry.
      const int base = sp;
      for (unsigned c = 0; c < 8; ++c) {
        const unsigned j = c ^ octant;
        float lo = p.t0, hi = p.t1;
        for (int a = 0; a < 3; ++a) {
          if ((j >> a) & 1u)
            lo = tm[a] > lo ? tm[a] : lo;
          else
            hi = tm[a] < hi ? tm[a] : hi;
        }
        if (!(lo <= hi) || !push(c, lo, hi)) continue;
        for (int k = sp - 1; k > base && stack[k - 1].t0 < stack[k].t0; --k)
          std::swap(stack[k], stack[k - 1]);
      }
    }
    return hit;
  }

  void build(std::span<const Aabb> boxes, std::uint64_t budget_bytes, const PrimitiveOverlap& overlap);

  OctreeParams params_;
  Aabb root_cell_{Vec3(0.0f), Vec3(0.0f)};
  std::vector<OctreeNode> nodes_;
  std::vector<std::uint32_t> prim_ids_;
  SphereSoA spheres_;  ///< The spheres of prim_ids_, when attached.
  BuildStats stats_;
};

}  // namespace accel
