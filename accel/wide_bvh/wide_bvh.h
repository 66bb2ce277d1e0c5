#pragma once
// Wide BVHs, `bvh4` and `bvh8`: W children per node, their boxes stored structure-of-arrays and
// tested against the ray in one SIMD step; closest-hit traversal visits the children front to
// back by entry distance, the any-hit traversal (shadow rays) in node order with no sorting and
// leaves first. Built directly by binned SAH (wide_bvh_builder.cpp): a node takes its range's
// SAH split, then keeps splitting its largest child until it has W. Leaves may hold their
// spheres structure-of-arrays (sphere_soa.h), tested several at a time.

#include "accel/build_limits.h"
#include "accel/bvh.h"
#include "accel/geometry.h"
#include "accel/interval_slack.h"
#include "accel/knob_table.h"
#include "accel/leaf_loop.h"
#include "accel/ray_setup.h"
#include "accel/simd.h"
#include "accel/sphere_soa.h"
#include "accel/stats.h"

#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace accel {

/// Knobs of a wide BVH; W (4 or 8) only names the table's owner, bvh4 or bvh8.
template <int W>
struct WideBvhParams {
  /// Centroid bins per axis the SAH evaluates, 8..256.
  int bins = 16;
  /// A range holding more primitives than this is always split; at or below it the SAH decides
  /// between a leaf and a split. 1..255.
  int max_leaf_size = W == 4 ? 4 : 8;
  /// Deepest level of wide nodes, root = 0; a range there is a leaf whatever it holds. 0..64.
  int max_depth = 64;
  /// Cost of one wide node step relative to one primitive test (the SAH's C_trav / C_isect).
  float traversal_cost = 3.0f;

  /// Name, range, unit and doc line of every knob above.
  static const KnobTable<WideBvhParams>& knobs();
};

/// W children per node, structure-of-arrays: the boxes' six planes (lo x, hi x, lo y, hi y,
/// lo z, hi z), each as W floats, then the children. An unused slot has an empty box (+inf,
/// -inf), which no ray enters.
template <int W>
struct alignas(64) WideNode {
  float planes[6][W];          ///< Child boxes: planes[2 a][i] lo, planes[2 a + 1][i] hi on axis a.
  std::uint32_t child[W];      ///< Inner child: node index; leaf: first index into the ids.
  std::uint32_t count[W];      ///< Leaf: primitives (> 0); inner child or unused slot: 0.
};
static_assert(sizeof(WideNode<4>) == 128, "a 4-wide node is two cache lines");
static_assert(sizeof(WideNode<8>) == 256, "an 8-wide node is four cache lines");

template <int W>
class WideBvh {
 public:
  using Params = WideBvhParams<W>;
  using Node = WideNode<W>;
  static constexpr const char* kName = W == 4 ? "bvh4" : "bvh8";
  static constexpr const char* kSummary =
      W == 4 ? "4-wide BVH, binned SAH, SoA nodes tested in one SIMD step, SIMD sphere leaves"
             : "8-wide BVH, binned SAH, SoA nodes tested in one SIMD step, SIMD sphere leaves";
  /// Traversal stack entries: a node pushes at most W - 1 children, 64 levels deep.
  static constexpr int kStackSize = (W - 1) * 64 + 1;

  WideBvh() = default;
  /// Builds over `boxes` (primitive id = index). Throws ConfigError for a bad knob or when the
  /// build would pass the memory budget of `limits`.
  WideBvh(std::span<const Aabb> boxes, const Params& params, const BuildLimits& limits);
  explicit WideBvh(std::span<const Aabb> boxes, const Params& params = {});

  /// Stores the spheres of a sphere-only scene (spheres[i] is primitive i) beside the leaves, so
  /// that leaves test them in SIMD for leaf functions that accept a precomputed t.
  /// The time it takes is added to stats().build_ms.
  void attach_spheres(std::span<const SphereShape> spheres) {
    if (spheres.size() != prim_ids_.size())
      throw std::invalid_argument(std::string(kName) + ": " + std::to_string(spheres.size()) +
                                  " spheres attached to a structure over " + std::to_string(prim_ids_.size()) +
                                  " primitives");
    const auto start = std::chrono::steady_clock::now();
    spheres_.build(prim_ids_, spheres);
    stats_.memory_bytes = memory_bytes();
    stats_.build_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }

  /// Closest hit: children front to back by entry distance; leaf_fn may shorten ray.tmax, and a
  /// child entered beyond it is skipped.
  template <bool Count = false, class LeafFn>
  void intersect(Ray& ray, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    if constexpr (Count) counters->rays++;
    if (nodes_.empty()) return;
    const RaySetup rs(ray);
    closest<Count>(ray, NodeRay(rs), leaf_fn, counters);
  }

  /// Any hit: true at the first primitive whose leaf_fn returns true. No ordering: a node's
  /// leaves are tested before its inner children are pushed.
  template <bool Count = false, class LeafFn>
  bool occluded(const Ray& ray_in, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    if constexpr (Count) counters->rays++;
    if (nodes_.empty()) return false;
    Ray ray = ray_in;
    const RaySetup rs(ray);
    return any_hit<Count>(ray, NodeRay(rs), leaf_fn, counters);
  }

  const Params& params() const { return params_; }
  const BuildStats& stats() const { return stats_; }
  /// The nodes, root first. Empty for zero primitives.
  std::span<const Node> nodes() const { return nodes_; }
  /// Original primitive ids in leaf order; a leaf covers [child, child + count).
  std::span<const std::uint32_t> prim_ids() const { return prim_ids_; }
  /// True when the leaves hold their spheres structure-of-arrays.
  bool has_sphere_leaves() const { return !spheres_.empty(); }

 private:
  /// The batch the box test runs on: W lanes where the target has them, else 4 at a time.
  using Batch = std::conditional_t<std::is_void_v<simd::FloatN<W>>, simd::Float4, simd::FloatN<W>>;
  static constexpr int kSteps = W / int(Batch::size);

  /// Per-ray data of the SIMD slab test: which plane row is near and far on each axis.
  struct NodeRay {
    float org[3];
    float inv_dir[3];
    float inv_far[3];  ///< inv_dir * (1 + 2 gamma(3)) for far distances (Ize 2013).
    int near_row[3];   ///< planes row of the near plane on each axis (lo unless the ray goes down).
    explicit NodeRay(const RaySetup& rs) {
      for (int a = 0; a < 3; ++a) {
        org[a] = rs.org[a];
        inv_dir[a] = rs.inv_dir[a];
        inv_far[a] = rs.inv_dir[a] * kSlabFarScale;
        near_row[a] = 2 * a + rs.neg[a];
      }
    }
  };

  /// Entry distances of the ray into the children of `n` within [t_lo, t_hi]: bit i of the
  /// result is set when child i is entered, at tn[i]. Each lane performs Bvh::enter's
  /// operations: a 0 * inf = NaN slab distance leaves the interval unchanged.
  static std::uint32_t enter(const Node& n, const NodeRay& r, float t_lo, float t_hi, float* tn) {
    std::uint32_t bits = 0;
    for (int s = 0; s < kSteps; ++s) {
      const int o = s * int(Batch::size);
      Batch t0(t_lo), t1(t_hi);
      for (int a = 0; a < 3; ++a) {
        const Batch org(r.org[a]);
        const Batch t_near = (Batch::load_aligned(n.planes[r.near_row[a]] + o) - org) * Batch(r.inv_dir[a]);
        const Batch t_far = (Batch::load_aligned(n.planes[r.near_row[a] ^ 1] + o) - org) * Batch(r.inv_far[a]);
        t0 = xsimd::select(t_near > t0, t_near, t0);
        t1 = xsimd::select(t_far < t1, t_far, t1);
      }
      t0.store_unaligned(tn + o);
      bits |= simd::mask_bits<Batch>(t0 <= t1) << o;
    }
    return bits;
  }

  /// A child waiting on the stack.
  struct Entry {
    std::uint32_t child;  ///< Node index, or first primitive of a leaf.
    std::uint32_t count;  ///< Leaf primitives; 0 for an inner node.
    float t;              ///< Entry distance, checked against the (shorter) t_hi when popped.
  };

  template <bool Count, class LeafFn>
  void closest(Ray& ray, const NodeRay& r, LeafFn& leaf_fn, TraversalCounters* counters) const {
    const float t_lo = widen_down(ray.tmin);
    float t_hi = widen_up(ray.tmax);
    Entry stack[kStackSize];
    int sp = 0;
    bool hit = false;
    std::uint32_t node = 0;
    alignas(64) float tn[W];
    for (;;) {
      if constexpr (Count) {
        counters->nodes_visited++;
        counters->boxes_tested += W;
      }
      const Node& n = nodes_[node];
      std::uint32_t bits = enter(n, r, t_lo, t_hi, tn);
      if (bits) {
        // Push every entered child but the nearest, farthest first; then take the nearest. A
        // leaf taken is tested at once.
        Entry near{0, 0, kInfinity};
        if (std::has_single_bit(bits)) {
          const int i = std::countr_zero(bits);
          near = {n.child[i], n.count[i], tn[i]};
        } else {
          Entry hits[W];
          int k = 0;
          do {
            const int i = std::countr_zero(bits);
            bits &= bits - 1u;
            Entry e{n.child[i], n.count[i], tn[i]};
            int j = k++;  // insertion sort, nearest last
            for (; j > 0 && hits[j - 1].t < e.t; --j) hits[j] = hits[j - 1];
            hits[j] = e;
          } while (bits);
          for (int j = 0; j < k - 1; ++j) stack[sp++] = hits[j];
          near = hits[k - 1];
        }
        if (near.count == 0) {
          node = near.child;
          continue;
        }
        test_leaf<Count, false>(prim_ids_.data(), spheres_, near.child, near.count, ray, leaf_fn, counters, hit);
        t_hi = widen_up(ray.tmax);
      }
      // Pop the nearest pending child that still starts before the current hit; leaves are
      // tested as they come off the stack.
      for (;;) {
        if (sp == 0) return;
        const Entry e = stack[--sp];
        if (e.t > t_hi) continue;
        if (e.count == 0) {
          node = e.child;
          break;
        }
        test_leaf<Count, false>(prim_ids_.data(), spheres_, e.child, e.count, ray, leaf_fn, counters, hit);
        t_hi = widen_up(ray.tmax);
      }
    }
  }

  template <bool Count, class LeafFn>
  bool any_hit(Ray& ray, const NodeRay& r, LeafFn& leaf_fn, TraversalCounters* counters) const {
    const float t_lo = widen_down(ray.tmin);
    const float t_hi = widen_up(ray.tmax);
    std::uint32_t stack[kStackSize];
    int sp = 0;
    bool hit = false;
    std::uint32_t node = 0;
    alignas(64) float tn[W];
    for (;;) {
      if constexpr (Count) {
        counters->nodes_visited++;
        counters->boxes_tested += W;
      }
      const Node& n = nodes_[node];
      std::uint32_t bits = enter(n, r, t_lo, t_hi, tn);
      while (bits) {
        const int i = std::countr_zero(bits);
        bits &= bits - 1u;
        if (n.count[i] == 0) {
          stack[sp++] = n.child[i];
        } else if (test_leaf<Count, true>(prim_ids_.data(), spheres_, n.child[i], n.count[i], ray, leaf_fn,
                                          counters, hit)) {
          return true;
        }
      }
      if (sp == 0) return false;
      node = stack[--sp];
    }
  }

  void build(std::span<const Aabb> boxes, std::uint64_t budget_bytes);
  std::uint64_t memory_bytes() const {
    return nodes_.size() * sizeof(Node) + prim_ids_.size() * sizeof(std::uint32_t) + spheres_.memory_bytes();
  }

  Params params_;
  std::vector<Node, CacheLineAllocator<Node>> nodes_;
  std::vector<std::uint32_t> prim_ids_;
  SphereSoA spheres_;
  BuildStats stats_;
};

/// The 4-wide BVH (`bvh4`).
using Bvh4 = WideBvh<4>;
/// The 8-wide BVH (`bvh8`).
using Bvh8 = WideBvh<8>;

extern template class WideBvh<4>;
extern template class WideBvh<8>;

}  // namespace accel
