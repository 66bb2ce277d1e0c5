#pragma once
// A photon kd-tree with leaf buckets: inner cells split one axis at a plane, leaves hold up to
// leaf_size photons stored contiguously. Nodes are accel's 8-byte kd-tree node (the lower child
// follows its parent, the upper child's index is stored). Built by the sliding-midpoint rule
// (sliding_midpoint_builder.cpp, unbalanced) or the median rule (median_bucket_builder.cpp,
// balanced); the recursion they share is bucket_builder.h.
//
// The search keeps, per cell, the offset of the query from the cell along each axis (Arya and
// Mount's incremental distance): a far child's lower bound is the squared length of that offset
// vector with the split axis replaced by the query's distance to the plane, summed in the same
// order as distance2(), so it never exceeds the distance of a photon inside (neighbor_heap.h).

#include "photon.h"
#include "photon_tree_stats.h"

#include "accel/geometry.h"
#include "accel/kdtree.h"

#if defined(__AVX__)
#include <immintrin.h>
#endif

#include <array>
#include <bit>
#include <cstdint>
#include <span>
#include <vector>

namespace photon {

class BucketTree {
 public:
  /// Deepest level the builder makes (root = 0); a cell there is a leaf whatever it holds.
  static constexpr int kMaxDepth = 60;
  static constexpr int kStackSize = kMaxDepth + 4;

  BucketTree() = default;
  /// Builds over `photons` (original index = position in the span) with the sliding-midpoint
  /// rule and leaves of at most `leaf_size` photons (except cells of coincident photons and
  /// cells at kMaxDepth).
  static BucketTree sliding_midpoint(std::span<const Photon> photons, int leaf_size);
  /// The same with the median rule (a balanced tree).
  static BucketTree median(std::span<const Photon> photons, int leaf_size);
  /// A built tree: photons and their original indices in leaf order, nodes root first.
  BucketTree(std::vector<Photon> photons, std::vector<std::uint32_t> ids,
             std::vector<accel::KdNode> nodes, const accel::Aabb& bounds, PhotonTreeStats stats)
      : photons_(std::move(photons)), ids_(std::move(ids)), nodes_(std::move(nodes)),
        bounds_(bounds), stats_(stats) {
    // Coordinates again, one array per axis, padded so that a leaf's last block of kLanes
    // loads stay inside (the padding is never offered).
    const std::size_t padded = photons_.size() + kLanes;
    for (int a = 0; a < 3; ++a) coords_[a].assign(padded, 0.0f);
    for (std::size_t i = 0; i < photons_.size(); ++i)
      for (int a = 0; a < 3; ++a) coords_[a][i] = photons_[i].position[a];
    stats_.photons = photons_.size();
    stats_.nodes = nodes_.size();
    stats_.memory_bytes = photons_.capacity() * sizeof(Photon) +
                          ids_.capacity() * sizeof(std::uint32_t) +
                          nodes_.capacity() * sizeof(accel::KdNode) + 3 * padded * sizeof(float);
  }

  /// Photons in leaf order.
  std::span<const Photon> storage() const { return photons_; }
  /// Original index of the photon in each slot.
  const std::uint32_t* ids() const { return ids_.data(); }
  std::size_t size() const { return photons_.size(); }
  std::span<const accel::KdNode> nodes() const { return nodes_; }
  /// The root cell: the photons' bounding box.
  const accel::Aabb& bounds() const { return bounds_; }
  const PhotonTreeStats& stats() const { return stats_; }

  template <class State>
  void search(State& s) const {
    if (photons_.empty()) return;
    const float q[3] = {s.query().x, s.query().y, s.query().z};
    // Offsets of the query from the root cell (0 inside), then their squared length.
    float off[3];
    for (int a = 0; a < 3; ++a) {
      const float below = bounds_.lo[a] - q[a], above = q[a] - bounds_.hi[a];
      off[a] = below > 0.0f ? below : (above > 0.0f ? above : 0.0f);
    }
    if (off[0] * off[0] + off[1] * off[1] + off[2] * off[2] > s.bound2()) return;
    struct Pending {
      std::uint32_t node;
      float bound2;
      float off[3];
    };
    Pending stack[kStackSize];
    int sp = 0;
    std::uint32_t node = 0;
    const accel::KdNode* nodes = nodes_.data();
    for (;;) {
      s.count_node();
      const accel::KdNode n = nodes[node];
      if (!n.is_leaf()) {
        const int axis = n.axis();
        const float delta = q[axis] - n.split();
        const std::uint32_t lower = node + 1, upper = n.upper_child();
        Pending far{delta < 0.0f ? upper : lower, 0.0f, {off[0], off[1], off[2]}};
        far.off[axis] = delta;
        far.bound2 = far.off[0] * far.off[0] + far.off[1] * far.off[1] + far.off[2] * far.off[2];
        if (far.bound2 <= s.bound2()) stack[sp++] = far;
        node = delta < 0.0f ? lower : upper;
        continue;
      }
      scan_leaf(s, n.prim_begin(), n.prim_begin() + n.prim_count());
      for (;;) {
        if (sp == 0) return;
        const Pending& e = stack[--sp];
        if (e.bound2 <= s.bound2()) {
          node = e.node;
          off[0] = e.off[0], off[1] = e.off[1], off[2] = e.off[2];
          break;
        }
      }
    }
  }

 private:
  /// Photons whose squared distances one leaf block computes at once.
  static constexpr std::uint32_t kLanes = 8;

  /// Offers the photons in slots [begin, end). With AVX, eight squared distances at a time from
  /// the per-axis coordinate arrays (the same operations in the same order as distance2(), each
  /// rounded on its own, so the same bits), and only those within the bound go to the heap,
  /// which spares a mispredicted branch per rejected photon.
  template <class State>
  void scan_leaf(State& s, std::uint32_t begin, std::uint32_t end) const {
#if defined(__AVX__)
    const Vec3& q = s.query();
    const __m256 qx = _mm256_set1_ps(q.x), qy = _mm256_set1_ps(q.y), qz = _mm256_set1_ps(q.z);
    s.count_tested(end - begin);
    for (std::uint32_t i = begin; i < end; i += kLanes) {
      const __m256 dx = _mm256_sub_ps(qx, _mm256_loadu_ps(coords_[0].data() + i));
      const __m256 dy = _mm256_sub_ps(qy, _mm256_loadu_ps(coords_[1].data() + i));
      const __m256 dz = _mm256_sub_ps(qz, _mm256_loadu_ps(coords_[2].data() + i));
      const __m256 d2 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)),
                                      _mm256_mul_ps(dz, dz));
      unsigned mask = unsigned(
          _mm256_movemask_ps(_mm256_cmp_ps(d2, _mm256_set1_ps(s.bound2()), _CMP_LE_OQ)));
      if (end - i < kLanes) mask &= (1u << (end - i)) - 1u;
      if (!mask) continue;
      alignas(32) float lane[kLanes];
      _mm256_store_ps(lane, d2);
      for (; mask; mask &= mask - 1) {
        const int j = std::countr_zero(mask);
        s.offer(i + std::uint32_t(j), lane[j]);
      }
    }
#else
    for (std::uint32_t i = begin; i < end; ++i) s.consider(i);
#endif
  }

  std::vector<Photon> photons_;
  std::array<std::vector<float>, 3> coords_;  // x, y, z of photons_, padded by kLanes
  std::vector<std::uint32_t> ids_;
  std::vector<accel::KdNode> nodes_;
  accel::Aabb bounds_;
  PhotonTreeStats stats_;
};

}  // namespace photon
