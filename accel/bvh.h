#pragma once
// Bounding volume hierarchy: binned SAH build (bvh_builder.cpp), Wald's 32-byte node, ordered
// traversal (nearer child first) with a small fixed stack.

#include "cache_line_allocator.h"
#include "geometry.h"
#include "interval_slack.h"
#include "knobs/knob_table.h"
#include "leaf_loop.h"
#include "primitive_overlap.h"
#include "ray_setup.h"
#include "sphere_soa.h"
#include "stats.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <new>
#include <span>
#include <utility>
#include <vector>

namespace accel {

struct BuildLimits;

/// Knobs of the binned SAH builder.
struct BvhParams {
  /// Centroid bins per axis the SAH evaluates; more bins approach a full sweep.
  int bins = 16;
  /// A node holding more primitives than this is always split (unless max_depth stops it);
  /// at or below it the SAH decides between a leaf and a split.
  int max_leaf_size = 4;
  /// Deepest level, root = 0: a node at this depth is a leaf whatever it holds.
  int max_depth = 64;
  /// Cost of one traversal step relative to one primitive test (the SAH's C_trav / C_isect).
  /// 3 traced spheres8000 fastest (1 gave leaves of one sphere and 20% more node visits).
  float traversal_cost = 3.0f;
  /// Threads the build may use (0 = every core). The tree is the same at any count.
  int build_threads = 1;
  /// Extra primitive references spatial splits may add, as a share of the primitives; 0 builds
  /// without them. Above 0 the build is Stich et al.'s SBVH (spatial_split_builder.h), on one thread.
  float spatial_split_budget = 0.0f;

  /// Name, range, unit and doc line of every knob above.
  static const knobs::KnobTable<BvhParams>& knobs();
};

/// Wald's 32-byte node: the box, then for a leaf its primitive range, for an inner node the
/// index of its first child (the second child follows it).
struct BvhNode {
  float lo[3];          ///< Minimum corner of the box.
  std::uint32_t first;  ///< Leaf: first index into the primitive ids; inner: left child index.
  float hi[3];          ///< Maximum corner of the box.
  std::uint32_t count;  ///< Leaf: number of primitives (> 0); inner node: 0.

  bool is_leaf() const { return count != 0; }
};
static_assert(sizeof(BvhNode) == 32, "Wald's BVH node is 32 bytes");

class Bvh {
 public:
  using Params = BvhParams;
  static constexpr const char* kName = "bvh";
  static constexpr const char* kSummary = "binned SAH BVH, Wald's 32-byte node, ordered traversal";
  /// Traversal stack entries; a tree is at most 64 levels deep and each level pushes one.
  static constexpr int kStackSize = 64;

  Bvh() = default;
  /// Builds over `boxes` (primitive id = index). Throws knobs::ConfigError when the nodes would pass
  /// the memory budget of `limits`.
  Bvh(std::span<const Aabb> boxes, const BvhParams& params, const BuildLimits& limits);
  explicit Bvh(std::span<const Aabb> boxes, const BvhParams& params = {});

  /// Closest hit: visits leaves front to back, calling leaf_fn(prim_id, ray), which may
  /// shorten ray.tmax; boxes entered beyond the current ray.tmax are skipped.
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
    std::vector<LeafRange> leaves;
    for (const BvhNode& n : nodes_)
      if (n.is_leaf()) leaves.push_back({n.first, n.count});
    attach_sphere_leaves(kName, prim_ids_, leaves, spheres, spheres_, stats_);
  }

  const BvhParams& params() const { return params_; }
  const BuildStats& stats() const { return stats_; }
  /// The nodes: the root at 0, an unused node at 1 (so that siblings start at an even index),
  /// then sibling pairs. Empty for zero primitives.
  std::span<const BvhNode> nodes() const { return nodes_; }
  /// Original primitive ids in leaf order; a leaf covers [first, first + count).
  std::span<const std::uint32_t> prim_ids() const { return prim_ids_; }

 private:
  /// Per-ray data of the slab test.
  struct NodeRay {
    Vec3 org;      ///< Ray origin.
    Vec3 inv_dir;  ///< 1 / dir per component; +-inf for a +-0 component.
    Vec3 inv_far;  ///< inv_dir * (1 + 2 gamma(3)), for far distances (Ize 2013).
  };

  // Rounding: the boxes are padded outward at build time (pad_outward) and the ray interval is
  // widened (interval_slack.h) when a box is tested, so that a primitive whose computed t lies
  // on its box's face or ties the current hit exactly is still visited.

  /// Entry distance of the ray into node `n` within [t0, t1], or +inf when it misses. The
  /// direction octant picks the near and far planes at compile time; far distances use the
  /// reciprocal scaled by 1 + 2 gamma(3) (Ize 2013). A 0 * inf = NaN slab distance (a ray lying in a face plane)
  /// leaves the interval unchanged: NaN loses every comparison below.
  template <int Octant>
  static float enter(const BvhNode& n, const NodeRay& r, float t0, float t1) {
    constexpr bool nx = Octant & 1, ny = Octant & 2, nz = Octant & 4;
    const float near_x = ((nx ? n.hi[0] : n.lo[0]) - r.org.x) * r.inv_dir.x;
    const float near_y = ((ny ? n.hi[1] : n.lo[1]) - r.org.y) * r.inv_dir.y;
    const float near_z = ((nz ? n.hi[2] : n.lo[2]) - r.org.z) * r.inv_dir.z;
    const float far_x = ((nx ? n.lo[0] : n.hi[0]) - r.org.x) * r.inv_far.x;
    const float far_y = ((ny ? n.lo[1] : n.hi[1]) - r.org.y) * r.inv_far.y;
    const float far_z = ((nz ? n.lo[2] : n.hi[2]) - r.org.z) * r.inv_far.z;
    t0 = near_x > t0 ? near_x : t0;
    t0 = near_y > t0 ? near_y : t0;
    t0 = near_z > t0 ? near_z : t0;
    t1 = far_x < t1 ? far_x : t1;
    t1 = far_y < t1 ? far_y : t1;
    t1 = far_z < t1 ? far_z : t1;
    return t0 <= t1 ? t0 : kInfinity;
  }

  template <bool Count, bool AnyHit, class LeafFn>
  bool traverse(Ray& ray, LeafFn& leaf_fn, TraversalCounters* counters) const {
    if constexpr (Count) counters->rays++;
    if (nodes_.empty()) return false;
    const Vec3 inv_dir(1.0f / ray.dir.x, 1.0f / ray.dir.y, 1.0f / ray.dir.z);
    const NodeRay r{ray.org, inv_dir, inv_dir * kSlabFarScale};
    const int octant = std::signbit(ray.dir.x) | (std::signbit(ray.dir.y) << 1) |
                       (std::signbit(ray.dir.z) << 2);
    switch (octant) {
      case 0: return traverse_octant<Count, AnyHit, 0>(ray, r, leaf_fn, counters);
      case 1: return traverse_octant<Count, AnyHit, 1>(ray, r, leaf_fn, counters);
      case 2: return traverse_octant<Count, AnyHit, 2>(ray, r, leaf_fn, counters);
      case 3: return traverse_octant<Count, AnyHit, 3>(ray, r, leaf_fn, counters);
      case 4: return traverse_octant<Count, AnyHit, 4>(ray, r, leaf_fn, counters);
      case 5: return traverse_octant<Count, AnyHit, 5>(ray, r, leaf_fn, counters);
      case 6: return traverse_octant<Count, AnyHit, 6>(ray, r, leaf_fn, counters);
      default: return traverse_octant<Count, AnyHit, 7>(ray, r, leaf_fn, counters);
    }
  }

  template <bool Count, bool AnyHit, int Octant, class LeafFn>
  bool traverse_octant(Ray& ray, const NodeRay& r, LeafFn& leaf_fn,
                       TraversalCounters* counters) const {
    const BvhNode* nodes = nodes_.data();
    const std::uint32_t* ids = prim_ids_.data();
    const float t_lo = widen_down(ray.tmin);
    float t_hi = widen_up(ray.tmax);

    struct Entry {
      std::uint32_t node;
      float t;  ///< Entry distance, checked again against the (shorter) t_hi when popped.
    };
    Entry stack[kStackSize];
    int sp = 0;
    bool hit = false;

    if constexpr (Count) counters->boxes_tested++;
    if (enter<Octant>(nodes[0], r, t_lo, t_hi) == kInfinity) return false;
    std::uint32_t node = 0;
    for (;;) {
      if constexpr (Count) counters->nodes_visited++;
      const BvhNode& n = nodes[node];
      if (n.is_leaf()) {
        if (test_leaf<Count, AnyHit>(ids, spheres_, n.first, n.count, ray, leaf_fn, counters, hit)) return true;
        t_hi = widen_up(ray.tmax);
      } else {
        if constexpr (Count) counters->boxes_tested += 2;
        const float ta = enter<Octant>(nodes[n.first], r, t_lo, t_hi);
        const float tb = enter<Octant>(nodes[n.first + 1], r, t_lo, t_hi);
        if (ta != kInfinity) {
          if (tb != kInfinity) {
            const bool a_first = ta <= tb;
            node = a_first ? n.first : n.first + 1;
            stack[sp++] = {a_first ? n.first + 1 : n.first, a_first ? tb : ta};
          } else {
            node = n.first;
          }
          continue;
        }
        if (tb != kInfinity) {
          node = n.first + 1;
          continue;
        }
      }
      // Pop the nearest pending node that still starts before the current hit.
      for (;;) {
        if (sp == 0) return hit;
        const Entry e = stack[--sp];
        if (e.t <= t_hi) {
          node = e.node;
          break;
        }
      }
    }
  }

  void build(std::span<const Aabb> boxes, std::uint64_t max_memory_bytes, const PrimitiveOverlap& overlap);

  BvhParams params_;
  std::vector<BvhNode, CacheLineAllocator<BvhNode>> nodes_;
  std::vector<std::uint32_t> prim_ids_;
  SphereSoA spheres_;  ///< The spheres of prim_ids_, when attached.
  BuildStats stats_;
};

}  // namespace accel
