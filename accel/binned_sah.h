#pragma once
// The binned SAH split search (Wald 2007) shared by the BVH builders: centroids binned along
// each axis, the best plane by the surface area heuristic, and the in-place partition that goes
// with it.
//
// The search works on its own copy of the primitives' boxes (with their ids beside them), which
// the partitions reorder, so every pass reads memory in order instead of following ids into the
// scene's boxes; on a million random spheres that chase was most of the build. A box is two
// 4-float batches, so binning and bounding take one SIMD min and max per box. A partition also
// returns the bounds of both sides, so no range is read again to bound it. The boxes are
// reordered exactly as std::partition would reorder ids (the same swaps), so the trees are the
// ones the id-based builder made.

#include "geometry.h"
#include "simd.h"

#include <algorithm>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace accel {

class BinnedSah {
 public:
  /// Best split of one range.
  struct Split {
    int axis = -1;           ///< -1: no plane separates the centroids.
    int bin = 0;             ///< Bins [0, bin) go left.
    float cost = kInfinity;  ///< SAH cost, in units of one primitive test.
  };

  /// A range's bounds: the union of its boxes, and the box of their centroids.
  struct Bounds {
    Aabb box, centroids;
  };

  /// Scratch the search holds per primitive while a build runs (a box and an id).
  static constexpr std::size_t kBytesPerPrimitive = 36;

  /// `bins` per axis; the split cost is traversal_cost + (A_L N_L + A_R N_R) / A.
  BinnedSah(std::span<const Aabb> boxes, int bins, float traversal_cost)
      : right_cost_(std::size_t(bins)), traversal_cost_(traversal_cost) {
    for (int axis = 0; axis < 3; ++axis) {
      axis_bins_[axis].resize(std::size_t(bins));
      bin_counts_[axis].resize(std::size_t(bins));
    }
    refs_.resize(boxes.size());
    ids_.resize(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      refs_[i] = Ref{{boxes[i].lo.x, boxes[i].lo.y, boxes[i].lo.z, 0.0f}, {boxes[i].hi.x, boxes[i].hi.y, boxes[i].hi.z, 0.0f}};
      ids_[i] = std::uint32_t(i);
    }
  }

  /// The bounds of boxes [begin, end).
  Bounds bounds(std::uint32_t begin, std::uint32_t end) const {
    Accumulator acc;
    for (std::uint32_t i = begin; i < end; ++i) acc.add(refs_[i]);
    return acc.bounds();
  }

  /// The cheapest plane for boxes [begin, end), whose centroids span `centroids` and whose box
  /// has half-area `area`; axis -1 when every centroid coincides.
  Split find(std::uint32_t begin, std::uint32_t end, const Aabb& centroids, float area) {
    Split best;
    const int bins = int(axis_bins_[0].size());
    // A flat range (area 0) still splits spatially: its children cost nothing but the step.
    const float inv_area = area > 0.0f ? 1.0f / area : 0.0f;
    // One pass bins every axis whose centroids spread (each box is read once, not once per
    // axis); then each axis is swept on its own.
    bool spread[3] = {};
    Binner which[3] = {};
    for (int axis = 0; axis < 3; ++axis) {
      spread[axis] = centroids.hi[axis] > centroids.lo[axis];
      if (spread[axis]) which[axis] = binner(centroids, axis);
      std::fill(axis_bins_[axis].begin(), axis_bins_[axis].end(), Bin{});
      std::fill(bin_counts_[axis].begin(), bin_counts_[axis].end(), 0u);
    }
    for (std::uint32_t i = begin; i < end; ++i) {
      const Ref& r = refs_[i];
      const Float4 lo = Float4::load_aligned(r.lo), hi = Float4::load_aligned(r.hi);
      alignas(16) float c[4];
      centroid(lo, hi).store_aligned(c);
      for (int axis = 0; axis < 3; ++axis) {
        if (!spread[axis]) continue;
        const auto k = std::size_t(which[axis](c[axis]));
        axis_bins_[axis][k].grow(lo, hi);
        bin_counts_[axis][k]++;
      }
    }
    for (int axis = 0; axis < 3; ++axis) {
      if (!spread[axis]) continue;
      const std::vector<Bin>& bins_of = axis_bins_[axis];
      const std::vector<std::uint32_t>& counts = bin_counts_[axis];
      // Sweep from the right storing the cost of every right part, then from the left.
      Bin acc;
      std::uint32_t n = 0;
      for (int k = bins - 1; k > 0; --k) {
        acc.grow(bins_of[std::size_t(k)]);
        n += counts[std::size_t(k)];
        right_cost_[std::size_t(k)] = n ? acc.box().half_area() * float(n) : 0.0f;
      }
      acc = Bin{};
      n = 0;
      for (int k = 1; k < bins; ++k) {
        acc.grow(bins_of[std::size_t(k - 1)]);
        n += counts[std::size_t(k - 1)];
        if (n == 0 || n == end - begin) continue;
        const float cost = traversal_cost_ + (acc.box().half_area() * float(n) + right_cost_[std::size_t(k)]) * inv_area;
        if (cost < best.cost) best = {axis, k, cost};
      }
    }
    return best;
  }

  /// Moves the boxes of `split`'s left side to the front of [begin, end) and returns where the
  /// right side starts, with both sides' bounds. Without a plane (axis -1) the range is cut in
  /// half in its current order.
  std::uint32_t partition(std::uint32_t begin, std::uint32_t end, const Aabb& centroids, const Split& split,
                          Bounds& left, Bounds& right) {
    if (split.axis < 0) {
      const std::uint32_t mid = begin + (end - begin) / 2;
      left = bounds(begin, mid);
      right = bounds(mid, end);
      return mid;
    }
    const Binner bin = binner(centroids, split.axis);
    const int axis = split.axis;
    const auto goes_left = [&](const Ref& r) { return bin(0.5f * (r.lo[axis] + r.hi[axis])) < split.bin; };
    Accumulator l, r;
    // std::partition's own loop (libstdc++), so the order matches it; each box's side is known
    // once, and its bounds go to that side then. [begin, first) is left, [last, end) right.
    std::uint32_t first = begin, last = end;
    while (true) {
      while (first != last && goes_left(refs_[first])) l.add(refs_[first++]);
      if (first == last) break;
      --last;  // refs_[first] goes right
      while (first != last && !goes_left(refs_[last])) r.add(refs_[last--]);
      if (first == last) {
        r.add(refs_[first]);
        break;
      }
      std::swap(refs_[first], refs_[last]);  // the one at last went left, the one at first right
      std::swap(ids_[first], ids_[last]);
      l.add(refs_[first++]);
      r.add(refs_[last]);
    }
    left = l.bounds();
    right = r.bounds();
    return first;
  }

  /// The primitive ids in the boxes' current order.
  void copy_ids(std::vector<std::uint32_t>& ids) const { ids = ids_; }

 private:
  using Float4 = simd::Float4;

  /// A box as two batches; the fourth lanes are 0 and never read.
  struct alignas(32) Ref {
    float lo[4];
    float hi[4];
  };

  /// Bit for bit Aabb::center() of the box, lane by lane.
  static Float4 centroid(const Float4& lo, const Float4& hi) { return Float4(0.5f) * (lo + hi); }

  /// A bin's box (starting empty), grown a box at a time.
  struct alignas(32) Bin {
    float lo[4] = {kInfinity, kInfinity, kInfinity, kInfinity};
    float hi[4] = {-kInfinity, -kInfinity, -kInfinity, -kInfinity};
    void grow(const Float4& blo, const Float4& bhi) {
      xsimd::min(Float4::load_aligned(lo), blo).store_aligned(lo);
      xsimd::max(Float4::load_aligned(hi), bhi).store_aligned(hi);
    }
    void grow(const Bin& b) { grow(Float4::load_aligned(b.lo), Float4::load_aligned(b.hi)); }
    Aabb box() const { return {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}}; }
  };

  /// The bounds of boxes and of their centroids, in registers while a pass runs.
  struct Accumulator {
    Float4 box_lo = Float4(kInfinity), box_hi = Float4(-kInfinity);
    Float4 c_lo = Float4(kInfinity), c_hi = Float4(-kInfinity);
    void add(const Ref& r) {
      const Float4 lo = Float4::load_aligned(r.lo), hi = Float4::load_aligned(r.hi);
      const Float4 c = centroid(lo, hi);
      box_lo = xsimd::min(box_lo, lo);
      box_hi = xsimd::max(box_hi, hi);
      c_lo = xsimd::min(c_lo, c);
      c_hi = xsimd::max(c_hi, c);
    }
    Bounds bounds() const {
      alignas(16) float v[4][4];
      box_lo.store_aligned(v[0]);
      box_hi.store_aligned(v[1]);
      c_lo.store_aligned(v[2]);
      c_hi.store_aligned(v[3]);
      return {{{v[0][0], v[0][1], v[0][2]}, {v[1][0], v[1][1], v[1][2]}},
              {{v[2][0], v[2][1], v[2][2]}, {v[3][0], v[3][1], v[3][2]}}};
    }
  };

  /// Maps a centroid coordinate to its bin; the same function bins and partitions, so both agree.
  struct Binner {
    float lo;
    float scale;
    int last;
    int operator()(float c) const {
      const int b = int((c - lo) * scale);
      return std::clamp(b, 0, last);
    }
  };

  Binner binner(const Aabb& centroids, int axis) const {
    const float extent = centroids.hi[axis] - centroids.lo[axis];
    const std::size_t bins = axis_bins_[0].size();
    return {centroids.lo[axis], float(bins) / extent, int(bins) - 1};
  }

  std::vector<Ref> refs_;
  std::vector<std::uint32_t> ids_;                ///< The primitive id of each of refs_.
  std::vector<Bin> axis_bins_[3];                 ///< Scratch of find(): the bins of each axis...
  std::vector<std::uint32_t> bin_counts_[3];      ///< ...and how many boxes each holds.
  std::vector<float> right_cost_;                 ///< Scratch of find(): SAH term of bins [k, bins).
  float traversal_cost_;
};

}  // namespace accel
