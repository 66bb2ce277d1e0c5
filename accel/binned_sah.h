#pragma once
// The binned SAH split search (Wald 2007) shared by the BVH builders: centroids binned along
// each axis, the best plane by the surface area heuristic, and the in-place partition of a range
// of primitive ids that goes with it.

#include "geometry.h"

#include <algorithm>
#include <cstdint>
#include <span>
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

  /// `bins` per axis; the split cost is traversal_cost + (A_L N_L + A_R N_R) / A.
  BinnedSah(std::span<const Aabb> boxes, int bins, float traversal_cost)
      : boxes_(boxes), right_cost_(std::size_t(bins)), traversal_cost_(traversal_cost) {
    for (auto& b : axis_bins_) b.resize(std::size_t(bins));
    centroids_.resize(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) centroids_[i] = boxes[i].center();
  }

  /// The union of the boxes of ids[begin, end), and the bounds of their centroids.
  void bounds(const std::uint32_t* ids, std::uint32_t begin, std::uint32_t end, Aabb& box, Aabb& centroids) const {
    box = centroids = Aabb{};
    for (std::uint32_t i = begin; i < end; ++i) {
      box.grow(boxes_[ids[i]]);
      centroids.grow(centroids_[ids[i]]);
    }
  }

  /// The cheapest plane for ids[begin, end), whose centroids span `centroids` and whose box has
  /// half-area `area`; axis -1 when every centroid coincides.
  Split find(const std::uint32_t* ids, std::uint32_t begin, std::uint32_t end, const Aabb& centroids, float area) {
    Split best;
    const int bins = int(axis_bins_[0].size());
    // A flat range (area 0) still splits spatially: its children cost nothing but the step.
    const float inv_area = area > 0.0f ? 1.0f / area : 0.0f;
    // One pass bins every axis whose centroids spread (each primitive's centroid and box are
    // read once, not once per axis); then each axis is swept on its own.
    bool spread[3] = {};
    Binner which[3] = {};
    for (int axis = 0; axis < 3; ++axis) {
      spread[axis] = centroids.hi[axis] > centroids.lo[axis];
      if (spread[axis]) which[axis] = binner(centroids, axis);
      std::fill(axis_bins_[axis].begin(), axis_bins_[axis].end(), Bin{});
    }
    for (std::uint32_t i = begin; i < end; ++i) {
      const Vec3& c = centroids_[ids[i]];
      const Aabb& box = boxes_[ids[i]];
      for (int axis = 0; axis < 3; ++axis) {
        if (!spread[axis]) continue;
        Bin& b = axis_bins_[axis][std::size_t(which[axis](c[axis]))];
        b.box.grow(box);
        b.count++;
      }
    }
    for (int axis = 0; axis < 3; ++axis) {
      if (!spread[axis]) continue;
      const std::vector<Bin>& bins_of = axis_bins_[axis];
      // Sweep from the right storing the cost of every right part, then from the left.
      Aabb acc;
      std::uint32_t n = 0;
      for (int k = bins - 1; k > 0; --k) {
        acc.grow(bins_of[std::size_t(k)].box);
        n += bins_of[std::size_t(k)].count;
        right_cost_[std::size_t(k)] = n ? acc.half_area() * float(n) : 0.0f;
      }
      acc = Aabb{};
      n = 0;
      for (int k = 1; k < bins; ++k) {
        acc.grow(bins_of[std::size_t(k - 1)].box);
        n += bins_of[std::size_t(k - 1)].count;
        if (n == 0 || n == end - begin) continue;
        const float cost = traversal_cost_ + (acc.half_area() * float(n) + right_cost_[std::size_t(k)]) * inv_area;
        if (cost < best.cost) best = {axis, k, cost};
      }
    }
    return best;
  }

  /// Moves the ids of `split`'s left side to the front of ids[begin, end); returns where the
  /// right side starts. Without a plane (axis -1) the range is cut in half in index order.
  std::uint32_t partition(std::uint32_t* ids, std::uint32_t begin, std::uint32_t end, const Aabb& centroids,
                          const Split& split) const {
    if (split.axis < 0) return begin + (end - begin) / 2;
    const Binner bin = binner(centroids, split.axis);
    const int axis = split.axis;
    return std::uint32_t(std::partition(ids + begin, ids + end,
                                        [&](std::uint32_t id) { return bin(centroids_[id][axis]) < split.bin; }) -
                         ids);
  }

 private:
  struct Bin {
    Aabb box;
    std::uint32_t count = 0;
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

  std::span<const Aabb> boxes_;
  std::vector<Vec3> centroids_;
  std::vector<Bin> axis_bins_[3];  ///< Scratch of find(): the bins of each axis.
  std::vector<float> right_cost_;  ///< Scratch of find(): SAH term of bins [k, bins).
  float traversal_cost_;
};

}  // namespace accel
