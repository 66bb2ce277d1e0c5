#pragma once
// The binned SAH split search (Wald 2007) shared by the BVH builders: centroids binned along
// each axis, the best plane by the surface area heuristic, and the in-place partition that goes
// with it.
//
// The search works on its own copy of the primitives' boxes (with their ids beside them), which
// the partitions reorder, so every pass reads memory in order instead of following ids into the
// scene's boxes; on a million random spheres that chase was most of the build. A box is two
// 4-float batches, so binning and bounding take one SIMD min and max per box. A partition also
// returns the bounds of both sides, so no range is read again to bound it.

#include "cache_line_allocator.h"
#include "geometry.h"
#include "simd.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

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
  /// The most bins per axis (the builders' `bins` knob stops there).
  static constexpr int kMaxBins = 256;
  /// Ranges at least this long are binned and bounded by several tasks (build_tasks.h); the
  /// bins merge by min, max and integer sums, which are exact in any order, so the split is the
  /// one a single pass finds.
  static constexpr std::uint32_t kParallelPass = 1u << 15;
  /// Ranges at least this long are binned into two sets of bins, merged at the end (bin_range).
  static constexpr std::uint32_t kTwoBinSets = 128;

  /// `bins` per axis (at most kMaxBins); the split cost is traversal_cost + (A_L N_L + A_R N_R) / A.
  BinnedSah(std::span<const Aabb> boxes, int bins, float traversal_cost)
      : bins_(std::clamp(bins, 2, kMaxBins)), traversal_cost_(traversal_cost) {
    refs_.resize(boxes.size());
    ids_.resize(boxes.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, boxes.size(), kParallelPass), [&](const auto& r) {
      for (std::size_t i = r.begin(); i < r.end(); ++i) {
        refs_[i] = Ref{{boxes[i].lo.x, boxes[i].lo.y, boxes[i].lo.z, 0.0f}, {boxes[i].hi.x, boxes[i].hi.y, boxes[i].hi.z, 0.0f}};
        ids_[i] = std::uint32_t(i);
      }
    });
  }

  /// The bounds of boxes [begin, end).
  Bounds bounds(std::uint32_t begin, std::uint32_t end) const {
    const auto pass = [&](std::uint32_t b, std::uint32_t e) {
      Accumulator acc;
      for (std::uint32_t i = b; i < e; ++i) acc.add(refs_[i]);
      return acc;
    };
    if (end - begin < kParallelPass) return pass(begin, end).bounds();
    return tbb::parallel_reduce(
               tbb::blocked_range<std::uint32_t>(begin, end, kParallelPass / 2), Accumulator{},
               [&](const auto& r, Accumulator acc) {
                 acc.merge(pass(r.begin(), r.end()));
                 return acc;
               },
               [](Accumulator a, const Accumulator& b) {
                 a.merge(b);
                 return a;
               })
        .bounds();
  }

  /// The cheapest plane for boxes [begin, end), whose centroids span `centroids` and whose box
  /// has half-area `area`; axis -1 when every centroid coincides. Safe to call on disjoint
  /// ranges from several threads.
  Split find(std::uint32_t begin, std::uint32_t end, const Aabb& centroids, float area) const {
    // A flat range (area 0) still splits spatially: its children cost nothing but the step.
    const float inv_area = area > 0.0f ? 1.0f / area : 0.0f;
    // One pass bins every axis whose centroids spread (each box is read once, not once per
    // axis); then the three axes are swept together (cheapest_plane).
    AxisBins axes;
    for (int axis = 0; axis < 3; ++axis) {
      axes.spread[axis] = centroids.hi[axis] > centroids.lo[axis];
      if (axes.spread[axis]) axes.which[axis] = binner(centroids, axis);
    }
    axes.reset(bins_);
    if (end - begin < kParallelPass) {
      bin_range(begin, end, axes);
    } else {
      axes = tbb::parallel_reduce(
          tbb::blocked_range<std::uint32_t>(begin, end, kParallelPass / 2), axes,
          [&](const auto& r, AxisBins part) {
            bin_range(r.begin(), r.end(), part);
            return part;
          },
          [&](AxisBins a, const AxisBins& b) {
            a.merge(b, bins_);
            return a;
          });
    }
    return cheapest_plane(axes, end - begin, inv_area);
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
    // Lomuto's partition without a branch on the side (which a branch predicts no better than a
    // coin): every box swaps with the first right-side box, and the left side grows by one when
    // the box went left. [begin, first) is left, [first, i) right. Each box's bounds go to its
    // side through a select, so both sides are bounded in the same pass.
    const Float4 inf(kInfinity), minus_inf(-kInfinity);
    Accumulator l, r;
    std::uint32_t first = begin;
    for (std::uint32_t i = begin; i < end; ++i) {
      const Ref box = refs_[i];
      const bool goes_left = bin(0.5f * (box.lo[axis] + box.hi[axis])) < split.bin;
      const std::uint32_t id = ids_[i];
      refs_[i] = refs_[first];
      ids_[i] = ids_[first];
      refs_[first] = box;
      ids_[first] = id;
      first += goes_left ? 1u : 0u;
      const Float4 lo = Float4::load_aligned(box.lo), hi = Float4::load_aligned(box.hi);
      const Float4 c = centroid(lo, hi);
      const auto to_left = Float4::batch_bool_type(goes_left);
      l.add_parts(xsimd::select(to_left, lo, inf), xsimd::select(to_left, hi, minus_inf),
                  xsimd::select(to_left, c, inf), xsimd::select(to_left, c, minus_inf));
      r.add_parts(xsimd::select(to_left, inf, lo), xsimd::select(to_left, minus_inf, hi),
                  xsimd::select(to_left, inf, c), xsimd::select(to_left, minus_inf, c));
    }
    // find() only offers planes with boxes on both sides; should the binning here ever disagree,
    // an empty side would make a chain of empty nodes, so the range is halved instead.
    if (first == begin || first == end) return partition(begin, end, centroids, Split{}, left, right);
    left = l.bounds();
    right = r.bounds();
    return first;
  }

  /// The primitive ids in the boxes' current order.
  void copy_ids(std::vector<std::uint32_t>& ids) const { ids.assign(ids_.begin(), ids_.end()); }

 private:
  using Float4 = simd::Float4;

  /// A box as two batches; the fourth lanes are 0 and never read.
  struct alignas(32) Ref {
    float lo[4];
    float hi[4];
  };

  /// Bit for bit Aabb::center() of the box, lane by lane.
  static Float4 centroid(const Float4& lo, const Float4& hi) { return Float4(0.5f) * (lo + hi); }

  /// A bin's box, grown a box at a time. Trivial, so that the 3 x kMaxBins bins of a search
  /// cost nothing until the `bins` in use are emptied.
  struct alignas(32) Bin {
    float lo[4];
    float hi[4];
    static Bin empty() {
      return {{kInfinity, kInfinity, kInfinity, kInfinity}, {-kInfinity, -kInfinity, -kInfinity, -kInfinity}};
    }
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
    /// Adds a box given as its corners and its centroid's lower and upper bound (the centroid
    /// twice, or +inf and -inf to add nothing).
    void add_parts(const Float4& lo, const Float4& hi, const Float4& c_low, const Float4& c_high) {
      box_lo = xsimd::min(box_lo, lo);
      box_hi = xsimd::max(box_hi, hi);
      c_lo = xsimd::min(c_lo, c_low);
      c_hi = xsimd::max(c_hi, c_high);
    }
    void merge(const Accumulator& o) {
      box_lo = xsimd::min(box_lo, o.box_lo);
      box_hi = xsimd::max(box_hi, o.box_hi);
      c_lo = xsimd::min(c_lo, o.c_lo);
      c_hi = xsimd::max(c_hi, o.c_hi);
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
    return {centroids.lo[axis], float(bins_) / extent, bins_ - 1};
  }

  /// The bins of the three axes of one find(), on the stack of the thread that runs it.
  struct AxisBins {
    bool spread[3] = {};  ///< Whether the axis' centroids spread (else it is not binned).
    Binner which[3] = {};
    /// bins[k][axis]: bin k of each axis side by side, as the sweep reads them. Only the first
    /// `bins` of each spread axis are used.
    Bin bins[kMaxBins][3];
    /// counts[k][axis]: the boxes in bin k of each axis, the axes side by side so that the sweep
    /// loads a bin's three counts as one batch (lane 3 stays 0).
    alignas(16) std::int32_t counts[kMaxBins][4];
    /// Empties the first n bins of every axis.
    void reset(int n) {
      std::fill_n(&bins[0][0], 3 * n, Bin::empty());
      std::fill_n(&counts[0][0], 4 * n, 0);
    }
    void merge(const AxisBins& o, int n) {
      for (int axis = 0; axis < 3; ++axis) {
        if (!spread[axis]) continue;
        for (int k = 0; k < n; ++k) {
          bins[k][axis].grow(o.bins[k][axis]);
          counts[k][axis] += o.counts[k][axis];
        }
      }
    }
  };

  /// The cheapest plane between the bins of `axes` (`total` boxes in all), or axis -1. The three
  /// axes are swept at once, one lane each: first from the right, storing the cost of every
  /// right part, then from the left. The floats are those of a scalar sweep, axis by axis and
  /// term by term (Aabb::half_area's order, no fused multiply-adds), and of equal costs the
  /// first plane in (axis, bin) order wins, so the tree does not depend on the SIMD width.
  Split cheapest_plane(const AxisBins& axes, std::uint32_t total, float inv_area) const {
    using Int4 = xsimd::batch<std::int32_t, Float4::arch_type>;
    // The same lane mask seen as float lanes and as integer lanes (both 4 x 32 bits).
    const auto as_float_mask = [](const Int4::batch_bool_type& m) {
      return Float4::batch_bool_type(_mm_castsi128_ps(__m128i(m)));
    };
    const auto as_int_mask = [](const Float4::batch_bool_type& m) {
      return Int4::batch_bool_type(_mm_castps_si128(__m128(m)));
    };
    Float4 right_cost[kMaxBins];
    SweepBoxes acc;
    Int4 n(0);
    // A plane with an empty right part is never priced (the left sweep masks it), so its
    // right cost need not be the scalar sweep's 0.
    for (int k = bins_ - 1; k > 0; --k) {
      acc.grow(axes.bins, k);
      n += Int4::load_aligned(axes.counts[k]);
      right_cost[k] = acc.half_areas() * xsimd::batch_cast<float>(n);
    }
    alignas(16) const std::int32_t spread_lanes[4] = {-std::int32_t(axes.spread[0]), -std::int32_t(axes.spread[1]),
                                                      -std::int32_t(axes.spread[2]), 0};
    const Int4 spread = Int4::load_aligned(spread_lanes);
    const Int4 all = Int4(std::int32_t(total)), zero = Int4(0);
    const Float4 trav(traversal_cost_), inv(inv_area);
    Float4 best_cost(kInfinity);
    Int4 best_bin(0);
    acc = SweepBoxes{};
    n = zero;
    for (int k = 1; k < bins_; ++k) {
      acc.grow(axes.bins, k - 1);
      n += Int4::load_aligned(axes.counts[k - 1]);
      // Both parts hold boxes. A plane after an empty bin costs exactly what the plane before
      // it costs, so it never beats it and needs no mask.
      const auto priced = (n > zero) & (n < all) & (spread != zero);
      const Float4 cost = trav + (acc.half_areas() * xsimd::batch_cast<float>(n) + right_cost[k]) * inv;
      const auto better = as_float_mask(priced) & (cost < best_cost);
      best_cost = xsimd::select(better, cost, best_cost);
      best_bin = xsimd::select(as_int_mask(better), Int4(k), best_bin);
    }
    alignas(16) float costs[4];
    alignas(16) std::int32_t bins[4];
    best_cost.store_aligned(costs);
    best_bin.store_aligned(bins);
    Split best;
    for (int axis = 0; axis < 3; ++axis)
      if (costs[axis] < best.cost) best = {axis, bins[axis], costs[axis]};
    return best;
  }

  /// The boxes of a sweep's three parts, one per axis binned, as their corners.
  struct SweepBoxes {
    Float4 lo[3] = {Float4(kInfinity), Float4(kInfinity), Float4(kInfinity)};
    Float4 hi[3] = {Float4(-kInfinity), Float4(-kInfinity), Float4(-kInfinity)};
    /// Adds bin k of each axis to that axis' box.
    void grow(const Bin (&bins)[kMaxBins][3], int k) {
      for (int axis = 0; axis < 3; ++axis) {
        lo[axis] = xsimd::min(lo[axis], Float4::load_aligned(bins[k][axis].lo));
        hi[axis] = xsimd::max(hi[axis], Float4::load_aligned(bins[k][axis].hi));
      }
    }
    /// Lane a: Aabb::half_area() of axis a's box, e.x e.y + e.y e.z + e.z e.x, for a box that
    /// holds something (an empty one gives no number the sweep uses).
    Float4 half_areas() const {
      // The extents of the three boxes, transposed: x holds each box's x extent, and so on.
      __m128 x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2], w = _mm_setzero_ps();
      _MM_TRANSPOSE4_PS(x, y, z, w);
      const Float4 ex(x), ey(y), ez(z);
      return ex * ey + ey * ez + ez * ex;
    }
  };

  /// Adds boxes [begin, end) to the bins of every spread axis. The three bin indices come from
  /// one batch: lane by lane the Binner's float operations and its truncation, then its clamp.
  void bin_range(std::uint32_t begin, std::uint32_t end, AxisBins& axes) const {
    using Int4 = xsimd::batch<std::int32_t, Float4::arch_type>;
    alignas(16) float lo_lanes[4] = {0.0f, 0.0f, 0.0f, 0.0f}, scale_lanes[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int axis = 0; axis < 3; ++axis)
      if (axes.spread[axis]) {
        lo_lanes[axis] = axes.which[axis].lo;
        scale_lanes[axis] = axes.which[axis].scale;
      }
    const Float4 lo4 = Float4::load_aligned(lo_lanes), scale4 = Float4::load_aligned(scale_lanes);
    const Int4 zero(0), last(bins_ - 1);
    const auto add = [&](std::uint32_t i, AxisBins& to) {
      const Ref& r = refs_[i];
      const Float4 lo = Float4::load_aligned(r.lo), hi = Float4::load_aligned(r.hi);
      alignas(16) std::int32_t k[4];
      // An axis that does not spread lands in bin 0 (scale 0), whose contents find() never reads.
      xsimd::clip(xsimd::batch_cast<std::int32_t>((centroid(lo, hi) - lo4) * scale4), zero, last).store_aligned(k);
      for (int axis = 0; axis < 3; ++axis) {
        to.bins[k[axis]][axis].grow(lo, hi);
        to.counts[k[axis]][axis]++;
      }
    };
    if (end - begin < kTwoBinSets) {
      for (std::uint32_t i = begin; i < end; ++i) add(i, axes);
      return;
    }
    // Neighbouring boxes mostly share their bins, and a bin's update waits on the previous
    // one's store; alternating between two sets of bins halves that chain. On Zen 5 it took a
    // box's binning from 4.4 to 4.1 ns.
    AxisBins odd;
    odd.reset(bins_);
    std::uint32_t i = begin;
    for (; i + 1 < end; i += 2) {
      add(i, axes);
      add(i + 1, odd);
    }
    if (i < end) add(i, axes);
    axes.merge(odd, bins_);
  }

  // On huge pages once large (cache_line_allocator.h): at 10^6 primitives these 36 MB were
  // 9,000 page faults on 4 KiB pages.
  std::vector<Ref, CacheLineAllocator<Ref>> refs_;
  std::vector<std::uint32_t, CacheLineAllocator<std::uint32_t>> ids_;  ///< The primitive id of each of refs_.
  int bins_;
  float traversal_cost_;
};

}  // namespace accel
