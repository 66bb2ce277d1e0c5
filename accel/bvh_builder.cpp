// Binned SAH builder for Bvh (Wald 2007): centroids binned along each axis, the best plane by
// the surface area heuristic, an in-place partition of the primitive ids, nodes appended to one
// preallocated array with siblings adjacent.

#include "bvh.h"

#include "accel.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

namespace accel {
namespace {

struct Bin {
  Aabb box;
  std::uint32_t count = 0;
};

/// Best split found for one node.
struct Split {
  int axis = -1;          ///< -1: no plane separates the centroids.
  int bin = 0;            ///< Bins [0, bin) go left.
  float cost = kInfinity;  ///< SAH cost, in units of one primitive test.
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

Binner binner_for(const Aabb& centroids, int axis, int bins) {
  const float extent = centroids.hi[axis] - centroids.lo[axis];
  return {centroids.lo[axis], float(bins) / extent, bins - 1};
}

/// Pads a box outward by a few ulps of its coordinates, so a primitive whose computed hit lies
/// on its box's face is never culled by the rounding of the slab test (see kIntervalSlack).
void pad_outward(BvhNode& n) {
  constexpr float rel = 4.0f * std::numeric_limits<float>::epsilon();
  for (int a = 0; a < 3; ++a) {
    const float m = std::max(std::abs(n.lo[a]), std::abs(n.hi[a]));
    n.lo[a] -= m * rel;
    n.hi[a] += m * rel;
  }
}

class Builder {
 public:
  using Nodes = std::vector<BvhNode, CacheLineAllocator<BvhNode>>;

  Builder(std::span<const Aabb> boxes, const BvhParams& params, Nodes& nodes,
          std::vector<std::uint32_t>& ids, BuildStats& stats)
      : boxes_(boxes), params_(params), nodes_(nodes), ids_(ids), stats_(stats) {
    centroids_.resize(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) centroids_[i] = boxes[i].center();
    bins_.resize(std::size_t(params.bins));
    right_cost_.resize(std::size_t(params.bins));
  }

  void run() {
    nodes_.push_back({});  // the root
    nodes_.push_back({});  // unused: sibling pairs start at even indices, one cache line each
    build_node(0, 0, std::uint32_t(ids_.size()), 0);
  }

 private:
  void build_node(std::uint32_t index, std::uint32_t begin, std::uint32_t end, int depth) {
    Aabb box, centroids;
    for (std::uint32_t i = begin; i < end; ++i) {
      box.grow(boxes_[ids_[i]]);
      centroids.grow(centroids_[ids_[i]]);
    }
    set_box(nodes_[index], box);
    stats_.max_depth_reached = std::max(stats_.max_depth_reached, depth);
    const std::uint32_t count = end - begin;
    const float area = box.half_area();

    if (count == 1 || depth >= params_.max_depth) return make_leaf(index, begin, count, area);

    const Split split = find_split(begin, end, centroids, area);
    std::uint32_t mid;
    if (split.axis < 0) {
      // Every centroid coincides: no plane separates them. Split the range in half when the
      // leaf would be too big, otherwise keep it.
      if (count <= std::uint32_t(params_.max_leaf_size)) return make_leaf(index, begin, count, area);
      mid = begin + count / 2;
    } else {
      if (count <= std::uint32_t(params_.max_leaf_size) && float(count) <= split.cost)
        return make_leaf(index, begin, count, area);
      const Binner bin = binner_for(centroids, split.axis, params_.bins);
      const int axis = split.axis;
      const auto it = std::partition(ids_.begin() + begin, ids_.begin() + end,
                                     [&](std::uint32_t id) { return bin(centroids_[id][axis]) < split.bin; });
      mid = std::uint32_t(it - ids_.begin());
    }

    const auto left = std::uint32_t(nodes_.size());
    nodes_[index].first = left;
    nodes_[index].count = 0;
    nodes_.push_back({});
    nodes_.push_back({});
    stats_.sah_cost += kStatsTraversalCost * area;
    build_node(left, begin, mid, depth + 1);
    build_node(left + 1, mid, end, depth + 1);
  }

  Split find_split(std::uint32_t begin, std::uint32_t end, const Aabb& centroids, float area) {
    Split best;
    const int bins = params_.bins;
    // A flat node (area 0) still splits spatially: its children cost nothing but the step.
    const float inv_area = area > 0.0f ? 1.0f / area : 0.0f;
    for (int axis = 0; axis < 3; ++axis) {
      if (!(centroids.hi[axis] > centroids.lo[axis])) continue;
      std::vector<Bin>& bin = bins_;
      std::fill(bin.begin(), bin.end(), Bin{});
      const Binner which = binner_for(centroids, axis, bins);
      for (std::uint32_t i = begin; i < end; ++i) {
        Bin& b = bin[std::size_t(which(centroids_[ids_[i]][axis]))];
        b.box.grow(boxes_[ids_[i]]);
        b.count++;
      }
      // Sweep from the right storing the cost of every right part, then from the left.
      std::vector<float>& right_cost = right_cost_;
      Aabb acc;
      std::uint32_t n = 0;
      for (int k = bins - 1; k > 0; --k) {
        acc.grow(bin[std::size_t(k)].box);
        n += bin[std::size_t(k)].count;
        right_cost[std::size_t(k)] = n ? acc.half_area() * float(n) : 0.0f;
      }
      acc = Aabb{};
      n = 0;
      for (int k = 1; k < bins; ++k) {
        acc.grow(bin[std::size_t(k - 1)].box);
        n += bin[std::size_t(k - 1)].count;
        if (n == 0 || n == end - begin) continue;
        const float cost =
            params_.traversal_cost + (acc.half_area() * float(n) + right_cost[std::size_t(k)]) * inv_area;
        if (cost < best.cost) best = {axis, k, cost};
      }
    }
    return best;
  }

  void make_leaf(std::uint32_t index, std::uint32_t begin, std::uint32_t count, float area) {
    nodes_[index].first = begin;
    nodes_[index].count = count;
    stats_.leaves++;
    stats_.max_leaf_prims = std::max<std::uint64_t>(stats_.max_leaf_prims, count);
    stats_.sah_cost += double(area) * double(count);
  }

  static void set_box(BvhNode& n, const Aabb& box) {
    for (int a = 0; a < 3; ++a) {
      n.lo[a] = box.lo[a];
      n.hi[a] = box.hi[a];
    }
  }

  // BuildStats::sah_cost is defined with traversal cost 1 whatever the builder's knob.
  static constexpr double kStatsTraversalCost = 1.0;

  std::span<const Aabb> boxes_;
  const BvhParams& params_;
  Nodes& nodes_;
  std::vector<std::uint32_t>& ids_;
  BuildStats& stats_;
  std::vector<Vec3> centroids_;
  std::vector<Bin> bins_;          ///< Scratch of find_split, one axis at a time.
  std::vector<float> right_cost_;  ///< Scratch of find_split: SAH term of bins [k, bins).
};

}  // namespace

void Bvh::build(std::span<const Aabb> boxes, std::uint64_t max_memory_bytes) {
  {
    BvhParams checked;  // the same range checks as the JSON knobs, for structs built in code
    from_json(nlohmann::json(params_), checked);
  }
  const auto start = std::chrono::steady_clock::now();
  const std::uint64_t n = boxes.size();
  const std::uint64_t node_bound = n ? 2 * n : 0;  // 2n - 1 nodes and the unused one
  const std::uint64_t bytes = node_bound * sizeof(BvhNode) + n * sizeof(std::uint32_t);
  if (bytes > max_memory_bytes)
    throw ConfigError("bvh: " + std::to_string(n) + " primitives need " + std::to_string(bytes) +
                      " bytes, over the memory budget of " + std::to_string(max_memory_bytes) +
                      " bytes (raise --max-memory)");

  nodes_.clear();
  prim_ids_.resize(n);
  std::iota(prim_ids_.begin(), prim_ids_.end(), 0u);
  stats_ = {};
  stats_.primitives = n;
  stats_.prim_refs = n;
  if (n > 0) {
    nodes_.reserve(node_bound);
    Builder(boxes, params_, nodes_, prim_ids_, stats_).run();
    const float root_area = Aabb{{nodes_[0].lo[0], nodes_[0].lo[1], nodes_[0].lo[2]},
                                 {nodes_[0].hi[0], nodes_[0].hi[1], nodes_[0].hi[2]}}
                                .half_area();
    // Normalised by the root's area; a flat or point-like root (area 0) costs its leaf tests.
    stats_.sah_cost = root_area > 0.0f ? stats_.sah_cost / root_area : double(n);
    for (BvhNode& node : nodes_) pad_outward(node);
  }
  nodes_.shrink_to_fit();
  stats_.nodes = nodes_.empty() ? 0 : nodes_.size() - 1;
  stats_.mean_leaf_prims = stats_.leaves ? double(n) / double(stats_.leaves) : 0.0;
  stats_.memory_bytes = nodes_.size() * sizeof(BvhNode) + prim_ids_.size() * sizeof(std::uint32_t);
  stats_.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace accel
