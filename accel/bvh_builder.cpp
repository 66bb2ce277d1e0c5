// Binned SAH builder for Bvh (Wald 2007): centroids binned along each axis, the best plane by
// the surface area heuristic, an in-place partition of the primitive ids, nodes allocated depth
// first with siblings adjacent. Large ranges build their children as parallel tasks
// (build_tasks.h); the tree is the same at any thread count.

#include "bvh.h"

#include "accel.h"
#include "binned_sah.h"
#include "build_tasks.h"
#include "spatial_split_builder.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

namespace accel {
namespace {

/// Pads a box outward by a few ulps of its coordinates, so a primitive whose computed hit lies
/// on its box's face is never culled by the rounding of the slab test (see interval_slack.h).
void pad_outward(BvhNode& n) {
  for (int a = 0; a < 3; ++a) {
    const float pad = box_pad(n.lo[a], n.hi[a]);
    n.lo[a] -= pad;
    n.hi[a] += pad;
  }
}

class Builder {
 public:
  using Slabs = NodeSlabs<BvhNode>;

  Builder(std::span<const Aabb> boxes, const BvhParams& params, std::uint64_t node_capacity)
      : params_(params), sah_(boxes, params.bins, params.traversal_cost), slabs_(node_capacity) {}

  /// Builds the tree and returns what it counted; then compact() and copy_ids() read it out.
  BuildTally run(std::uint32_t n) {
    Slabs::Cursor c = slabs_.whole();
    slabs_.allocate(c, 2);  // the root, then an unused node: sibling pairs start at even indices
    slabs_[1] = {};
    BuildTally tally;
    build_node(c, 0, 0, n, 0, sah_.bounds(0, n), tally);
    slabs_.close_run(c);
    return tally;
  }

  template <class Nodes>
  void compact(Nodes& nodes) {
    slabs_.compact(nodes, [](BvhNode& node, const auto& renumber) {
      if (!node.is_leaf()) node.first = renumber(node.first);
    });
  }

  void copy_ids(std::vector<std::uint32_t>& ids) const { sah_.copy_ids(ids); }

 private:
  void build_node(Slabs::Cursor& c, std::uint32_t index, std::uint32_t begin, std::uint32_t end, int depth,
                  const BinnedSah::Bounds& bounds, BuildTally& tally) {
    const Aabb& box = bounds.box;
    set_box(slabs_[index], box);
    tally.max_depth_reached = std::max(tally.max_depth_reached, depth);
    const std::uint32_t count = end - begin;
    const float area = box.half_area();

    if (count == 1 || depth >= params_.max_depth) return make_leaf(index, begin, count, area, tally);

    const BinnedSah::Split split = sah_.find(begin, end, bounds.centroids, area);
    // Every centroid coinciding (no plane), the range is cut in half when a leaf would be too
    // big; otherwise the SAH decides between a leaf and the split.
    const bool small = count <= std::uint32_t(params_.max_leaf_size);
    if (small && (split.axis < 0 || float(count) <= split.cost)) return make_leaf(index, begin, count, area, tally);
    BinnedSah::Bounds left_bounds, right_bounds;
    const std::uint32_t mid = sah_.partition(begin, end, bounds.centroids, split, left_bounds, right_bounds);

    const std::uint32_t left = slabs_.allocate(c, 2);
    slabs_[index].first = left;
    slabs_[index].count = 0;
    tally.sah += kStatsTraversalCost * area;
    if (count < kForkPrims) {
      build_node(c, left, begin, mid, depth + 1, left_bounds, tally);
      build_node(c, left + 1, mid, end, depth + 1, right_bounds, tally);
      return;
    }
    // Each child's subtree in a slab of its own. A child over m primitives has at most 2(m - 1)
    // descendants (every inner node two children, every leaf a primitive), which with the two
    // children allocated above is this node's own bound, 2(count - 1): the slabs never overlap.
    slabs_.close_run(c);
    Slabs::Cursor lc = slabs_.carve(c, 2 * (mid - begin - 1)), rc = slabs_.carve(c, 2 * (end - mid - 1));
    BuildTally lt, rt;
    tbb::parallel_invoke(
        [&] {
          build_node(lc, left, begin, mid, depth + 1, left_bounds, lt);
          slabs_.close_run(lc);
        },
        [&] {
          build_node(rc, left + 1, mid, end, depth + 1, right_bounds, rt);
          slabs_.close_run(rc);
        });
    tally.merge(lt);
    tally.merge(rt);
  }

  void make_leaf(std::uint32_t index, std::uint32_t begin, std::uint32_t count, float area, BuildTally& tally) {
    slabs_[index].first = begin;
    slabs_[index].count = count;
    tally.leaves++;
    tally.max_leaf_prims = std::max<std::uint64_t>(tally.max_leaf_prims, count);
    tally.sah += double(area) * double(count);
  }

  static void set_box(BvhNode& n, const Aabb& box) {
    for (int a = 0; a < 3; ++a) {
      n.lo[a] = box.lo[a];
      n.hi[a] = box.hi[a];
    }
  }

  // BuildStats::sah_cost is defined with traversal cost 1 whatever the builder's knob.
  static constexpr double kStatsTraversalCost = 1.0;

  const BvhParams& params_;
  BinnedSah sah_;
  Slabs slabs_;
};

}  // namespace

void Bvh::build(std::span<const Aabb> boxes, std::uint64_t max_memory_bytes, const PrimitiveOverlap& overlap) {
  BvhParams::knobs().validate(params_);  // the JSON knobs' checks, for structs built in code
  const auto start = std::chrono::steady_clock::now();
  const std::uint64_t n = boxes.size();
  const bool spatial = params_.spatial_split_budget > 0.0f;
  // Spatial splits may reference a primitive from several leaves, up to the budget.
  const std::uint64_t max_refs = spatial_split_max_refs(n, params_.spatial_split_budget);
  const std::uint64_t node_bound = max_refs ? 2 * max_refs : 0;  // 2r - 1 nodes and the unused one
  // The builder also holds one reference per primitive while it runs (the spatial one a box and
  // an id per reference, the node's and its children's).
  const std::uint64_t scratch = spatial ? 2 * sizeof(Aabb) + 8 : BinnedSah::kBytesPerPrimitive;
  const std::uint64_t bytes = node_bound * sizeof(BvhNode) + max_refs * (sizeof(std::uint32_t) + scratch);
  if (bytes > max_memory_bytes)
    throw knobs::ConfigError("bvh: " + std::to_string(n) + " primitives need " + std::to_string(bytes) +
                      " bytes, over the memory budget of " + std::to_string(max_memory_bytes) +
                      " bytes (raise --max-memory)");

  nodes_.clear();
  prim_ids_.clear();
  stats_ = {};
  stats_.primitives = n;
  BuildTally tally;
  if (n > 0 && spatial) {
    std::vector<BvhNode> nodes;
    tally = build_spatial_split_bvh(boxes, params_, overlap, max_refs, nodes, prim_ids_);
    nodes_.assign(nodes.begin(), nodes.end());
  } else if (n > 0) {
    prim_ids_.resize(n);  // the builder writes them in leaf order (BinnedSah::copy_ids)
    run_with_build_threads(params_.build_threads, [&] {
      Builder builder(boxes, params_, node_bound + 2);
      tally = builder.run(std::uint32_t(n));
      builder.compact(nodes_);
      builder.copy_ids(prim_ids_);
    });
  }
  if (n > 0) {
    const Aabb root{{nodes_[0].lo[0], nodes_[0].lo[1], nodes_[0].lo[2]}, {nodes_[0].hi[0], nodes_[0].hi[1], nodes_[0].hi[2]}};
    tally.write_to(stats_, root.half_area(), n);
  }
  for (BvhNode& node : nodes_) pad_outward(node);
  nodes_.shrink_to_fit();
  prim_ids_.shrink_to_fit();
  stats_.prim_refs = prim_ids_.size();
  stats_.nodes = nodes_.empty() ? 0 : nodes_.size() - 1;
  stats_.mean_leaf_prims = stats_.leaves ? double(prim_ids_.size()) / double(stats_.leaves) : 0.0;
  stats_.memory_bytes = nodes_.size() * sizeof(BvhNode) + prim_ids_.size() * sizeof(std::uint32_t);
  stats_.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace accel
