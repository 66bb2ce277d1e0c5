#pragma once
// The paper's kd-tree (section 3.2): a binary space partition that by default splits a cell's
// longest axis at its midpoint, with the surface area heuristic (pbrt-v3's cost model and
// empty-space bonus, costs measured for our sphere test) as the alternative split rule.
// pbrt-v3's 8-byte node; built in kdtree_builder.cpp (the SAH split search is kdtree_sah.cpp);
// traversed front to back with a small stack here.

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
#include <vector>

namespace accel {

struct BuildLimits;

/// How the kd-tree chooses a cell's split plane.
enum class SplitRule : std::uint8_t {
  /// The cell's longest axis at its midpoint (the paper's rule).
  Midpoint,
  /// The plane through a primitive box face with the least SAH cost (pbrt-v3), or a leaf when
  /// no split pays off.
  Sah,
};

/// Where the SAH kd-tree looks for split planes.
enum class SplitCandidates : std::uint8_t {
  /// The faces of each primitive's bounding box (pbrt-v3).
  Boxes,
  /// The faces of the box around each primitive's part inside the cell: a triangle clipped to
  /// the cell (Havran's "perfect splits"); other primitives keep their boxes.
  Clipped,
};

/// Knobs of the kd-tree. The defaults are the paper's midpoint rule and pbrt-v3's SAH cost
/// model with costs fitted to our sphere test; depth 24 is about pbrt-v3's 8 + 1.3 log2(N) for the
/// 8000-sphere scene, and leaves of 4 trace faster there than leaves of 1 or 2 (a sphere test
/// costs less than a cell step).
///
/// SAH costs: pbrt-v3's 1 / 80 / 0.5 (traversal, intersection, empty bonus) are calibrated for
/// its expensive general shapes; our sphere test costs about half a cell step, hence
/// intersection_cost 0.5. The empty bonus is what matters: at 0.5 the search spends the depth
/// budget shaving thin empty slabs off cells and leaves large leaves. The fit and the timings
/// behind these defaults: docs/structures.md ("kd-tree SAH costs").
struct KdTreeParams {
  /// Deepest level a cell may be split to, root = 0; a cell at this depth is a leaf.
  int max_depth = 24;
  /// A cell holding this many primitives or fewer is a leaf.
  int max_leaf_size = 4;
  /// Where a primitive straddling a split plane is stored.
  Placement placement = Placement::Leaves;
  /// How split planes are chosen.
  SplitRule split = SplitRule::Midpoint;
  /// Where the SAH looks for split planes (split sah only).
  SplitCandidates split_candidates = SplitCandidates::Clipped;
  /// SAH cost of one traversal step, in the same units as intersection_cost (pbrt-v3: 1).
  float traversal_cost = 1.0f;
  /// SAH cost of one primitive test, fitted for a sphere test (pbrt-v3: 80).
  float intersection_cost = 0.5f;
  /// Fraction of the SAH cost forgiven when a split leaves one side empty (pbrt-v3: 0.5).
  float empty_bonus = 0.2f;

  /// Name, range, unit and doc line of every knob above.
  static const knobs::KnobTable<KdTreeParams>& knobs();
};

/// pbrt-v3's 8-byte node. An inner node's lower child follows it; its upper child's index is
/// stored. A leaf's primitives are prim_ids[payload, payload + count).
struct KdNode {
  std::uint32_t payload = 0;  ///< Inner: the split position (float bits); leaf: first prim index.
  std::uint32_t bits = 3;     ///< Low 2 bits: split axis, or 3 for a leaf. High 30 bits:
                              ///< inner: index of the upper child; leaf: primitive count.

  static constexpr std::uint32_t kLeaf = 3;
  static constexpr std::uint32_t kMaxIndex = (1u << 30) - 1;

  static KdNode leaf(std::uint32_t first, std::uint32_t count) { return {first, (count << 2) | kLeaf}; }
  static KdNode inner(int axis, float split, std::uint32_t upper) {
    return {std::bit_cast<std::uint32_t>(split), (upper << 2) | std::uint32_t(axis)};
  }
  bool is_leaf() const { return (bits & 3u) == kLeaf; }
  int axis() const { return int(bits & 3u); }
  float split() const { return std::bit_cast<float>(payload); }
  std::uint32_t upper_child() const { return bits >> 2; }
  std::uint32_t prim_begin() const { return payload; }
  std::uint32_t prim_count() const { return bits >> 2; }
};
static_assert(sizeof(KdNode) == 8, "pbrt-v3's kd-tree node is 8 bytes");

/// With every_level placement, the primitives an inner node keeps (those straddling its split).
struct KdPrimRange {
  std::uint32_t begin = 0;  ///< First index into the primitive id array.
  std::uint32_t count = 0;  ///< Number of primitives.
};

class KdTree {
 public:
  using Params = KdTreeParams;
  static constexpr const char* kName = "kdtree";
  static constexpr const char* kSummary =
      "the paper's section 3.2 kd-tree: midpoint or SAH splits, pbrt-v3's 8-byte node";
  /// Traversal stack entries: one per level at most, and a tree is at most 64 levels deep.
  static constexpr int kStackSize = 64;

  KdTree() = default;
  /// Builds over `boxes` (primitive id = index). Throws knobs::ConfigError for a bad knob or when the
  /// build would pass the memory budget of `limits`.
  KdTree(std::span<const Aabb> boxes, const KdTreeParams& params, const BuildLimits& limits);
  explicit KdTree(std::span<const Aabb> boxes, const KdTreeParams& params = {});

  /// Closest hit: leaves front to back, calling leaf_fn(prim_id, ray), which may shorten
  /// ray.tmax; stops once the next cell starts beyond the current hit.
  template <bool Count = false, class LeafFn>
  void intersect(Ray& ray, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    if (inner_prims_.empty())
      traverse<Count, false, false>(ray, leaf_fn, counters);
    else
      traverse<Count, false, true>(ray, leaf_fn, counters);
  }

  /// Any hit: stops at the first primitive whose leaf_fn returns true.
  template <bool Count = false, class LeafFn>
  bool occluded(const Ray& ray_in, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    Ray ray = ray_in;
    if (inner_prims_.empty()) return traverse<Count, true, false>(ray, leaf_fn, counters);
    return traverse<Count, true, true>(ray, leaf_fn, counters);
  }

  /// Stores the spheres of a sphere-only scene (spheres[i] is primitive i) beside the id array,
  /// so that leaves test them in SIMD for leaf functions that accept a precomputed t
  /// (sphere_soa.h). The time it takes is added to stats().build_ms.
  void attach_spheres(std::span<const SphereShape> spheres) {
    std::vector<LeafRange> leaves;  // the leaves' primitives, and the inner nodes' (every_level)
    for (const KdNode& n : nodes_)
      if (n.is_leaf() && n.prim_count() > 0) leaves.push_back({n.prim_begin(), n.prim_count()});
    for (const KdPrimRange& r : inner_prims_)
      if (r.count > 0) leaves.push_back({r.begin, r.count});
    attach_sphere_leaves(kName, prim_ids_, leaves, spheres, spheres_, stats_);
  }

  const KdTreeParams& params() const { return params_; }
  const BuildStats& stats() const { return stats_; }
  /// The root cell: the union of the primitive boxes.
  const Aabb& bounds() const { return bounds_; }
  /// The nodes, root first.
  std::span<const KdNode> nodes() const { return nodes_; }
  /// Primitive ids of leaves and (every_level) inner nodes.
  std::span<const std::uint32_t> prim_ids() const { return prim_ids_; }
  /// Per node, the primitives an inner node keeps; empty unless placement is every_level.
  std::span<const KdPrimRange> inner_prims() const { return inner_prims_; }

 private:
  // Cells whose entry ties the current hit within rounding are still visited (at a tie the
  // lower id wins whatever the visiting order), and a split plane within rounding of a cell's
  // end sends the ray into both children (interval_slack.h).

  template <bool Count, bool AnyHit, bool InnerPrims, class LeafFn>
  bool traverse(Ray& ray, LeafFn& leaf_fn, TraversalCounters* counters) const {
    if constexpr (Count) counters->rays++;
    if (prim_ids_.empty()) return false;
    const RaySetup rs(ray);
    float t0 = ray.tmin, t1 = ray.tmax;
    if constexpr (Count) counters->boxes_tested++;
    if (!slab_clip(bounds_, rs, t0, t1)) return false;
    // Plain arrays: glm's vec3 operator[] is a switch, too slow with the node's axis as index.
    const float org[3] = {rs.org.x, rs.org.y, rs.org.z};
    const float inv_dir[3] = {rs.inv_dir.x, rs.inv_dir.y, rs.inv_dir.z};

    struct Pending {
      std::uint32_t node;
      float t0, t1;
    };
    Pending stack[kStackSize];
    int sp = 0;
    std::uint32_t node = 0;
    bool hit = false;
    for (;;) {
      if constexpr (Count) counters->nodes_visited++;
      const KdNode n = nodes_[node];
      if constexpr (InnerPrims) {
        const KdPrimRange r = inner_prims_[node];
        if (test_leaf<Count, AnyHit>(prim_ids_.data(), spheres_, r.begin, r.count, ray, leaf_fn, counters, hit))
          return true;
      }
      if (!n.is_leaf()) {
        if constexpr (Count) counters->boxes_tested++;
        const int axis = n.axis();
        // The child the ray is in before it crosses the plane: the lower one for a positive
        // direction. With a +-0 component t_plane is +-inf and picks the side the origin is
        // on; with the origin in the plane too it is NaN, and both children get the whole
        // interval.
        const float t_plane = (n.split() - org[axis]) * inv_dir[axis];
        const std::uint32_t lower = node + 1, upper = n.upper_child();
        const std::uint32_t first = rs.neg[axis] ? upper : lower;
        const std::uint32_t second = rs.neg[axis] ? lower : upper;
        if (t_plane > widen_up(t1)) {
          node = first;
        } else if (t_plane < widen_down(t0)) {
          node = second;
        } else {
          stack[sp++] = {second, t_plane > t0 ? t_plane : t0, t1};
          node = first;
          t1 = t_plane < t1 ? t_plane : t1;
        }
        continue;
      }
      if (test_leaf<Count, AnyHit>(prim_ids_.data(), spheres_, n.prim_begin(), n.prim_count(), ray, leaf_fn,
                                   counters, hit))
        return true;
      // Next pending cell that starts before the current hit. A hit found beyond this leaf is
      // still a valid candidate: it has shortened ray.tmax. The stack is not sorted by entry
      // (a ray lying in a split plane pushes a cell with the same interval as the one it
      // enters), so a far cell is skipped rather than ending the traversal.
      do {
        if (sp == 0) return hit;
        --sp;
      } while (stack[sp].t0 > widen_up(ray.tmax));
      node = stack[sp].node;
      t0 = stack[sp].t0;
      t1 = stack[sp].t1;
    }
  }

  void build(std::span<const Aabb> boxes, std::uint64_t budget_bytes, const PrimitiveOverlap& overlap);

  KdTreeParams params_;
  Aabb bounds_{Vec3(0.0f), Vec3(0.0f)};
  std::vector<KdNode> nodes_;
  std::vector<std::uint32_t> prim_ids_;
  SphereSoA spheres_;  ///< The spheres of prim_ids_, when attached.
  std::vector<KdPrimRange> inner_prims_;
  BuildStats stats_;
};

}  // namespace accel
