// Spatial splits for the wide BVHs (knob spatial_split_budget): the binary BVH's spatial-split
// build (spatial_split_builder.h, Stich et al. 2009) collapsed into W-wide nodes the way the direct
// builder shapes them (wide_bvh_builder.cpp): a node takes a binary node's two children, then opens
// its child of largest surface area (leaves excepted) until it has W children. A primitive may be
// referenced from several leaves, each leaf's node box bounding only its part there; the leaves
// test whole primitives, which is correct wherever a ray meets them.

#include "wide_bvh.h"
#include "wide_node_fill.h"

#include "accel/build_tasks.h"
#include "accel/bvh.h"
#include "accel/spatial_split_builder.h"

#include <algorithm>

namespace accel {
namespace {

Aabb box_of(const BvhNode& b) { return {{b.lo[0], b.lo[1], b.lo[2]}, {b.hi[0], b.hi[1], b.hi[2]}}; }
float half_area_of(const BvhNode& b) { return box_of(b).half_area(); }

template <int W, class Nodes>
class Collapser {
 public:
  Collapser(std::span<const BvhNode> binary, int max_depth, Nodes& nodes)
      : bin_(binary), max_depth_(max_depth), nodes_(nodes) {}

  BuildTally run() {
    BuildTally tally;
    nodes_.clear();
    nodes_.reserve(bin_.size() / 2 + 1);  // each wide node consumes at least one binary inner node
    nodes_.resize(1);
    if (bin_[0].is_leaf() || max_depth_ <= 0) {
      // One leaf holds everything: the root node has that leaf as its only child.
      const Kid root{0, half_area_of(bin_[0]), true};
      write(0, &root, 1, tally);
      return tally;
    }
    build(0, 0, 0, tally);
    return tally;
  }

 private:
  /// A binary node as a child slot; `leaf` when it is a binary leaf or lies at the depth limit.
  struct Kid {
    std::uint32_t node;
    float area;
    bool leaf;
  };

  /// The id range a binary subtree's leaves cover: the builder writes the references in leaf
  /// order, depth first, left child first, so a subtree's leaves are one contiguous range.
  std::uint32_t range_begin(std::uint32_t b) const {
    while (!bin_[b].is_leaf()) b = bin_[b].first;
    return bin_[b].first;
  }
  std::uint32_t range_end(std::uint32_t b) const {
    while (!bin_[b].is_leaf()) b = bin_[b].first + 1;
    return bin_[b].first + bin_[b].count;
  }

  Kid kid(std::uint32_t b, int depth, BuildTally& tally) const {
    tally.max_depth_reached = std::max(tally.max_depth_reached, depth);
    return {b, half_area_of(bin_[b]), bin_[b].is_leaf() || depth >= max_depth_};
  }

  /// Fills wide node `index` (at `depth`) from binary inner node `b`, and its subtree.
  void build(std::uint32_t index, std::uint32_t b, int depth, BuildTally& tally) {
    Kid kids[W];
    kids[0] = kid(bin_[b].first, depth + 1, tally);
    kids[1] = kid(bin_[b].first + 1, depth + 1, tally);
    int k = 2;
    while (k < W) {
      const int widest = widest_inner_child(kids, k);
      if (widest < 0) break;
      const std::uint32_t opened = kids[widest].node;
      kids[widest] = kid(bin_[opened].first, depth + 1, tally);
      kids[k++] = kid(bin_[opened].first + 1, depth + 1, tally);
    }
    tally.sah += double(half_area_of(bin_[b]));  // one node step
    const std::uint32_t first_inner = write(index, kids, k, tally);
    std::uint32_t next = first_inner;
    for (int i = 0; i < k; ++i)
      if (!kids[i].leaf) build(next++, kids[i].node, depth + 1, tally);
  }

  /// Writes node `index` from its k children; inner children get consecutive new nodes.
  std::uint32_t write(std::uint32_t index, const Kid* kids, int k, BuildTally& tally) {
    int inner = 0;
    for (int i = 0; i < k; ++i) inner += kids[i].leaf ? 0 : 1;
    const std::uint32_t first_inner = std::uint32_t(nodes_.size());
    nodes_.resize(nodes_.size() + std::size_t(inner));
    std::uint32_t next = first_inner;
    typename Nodes::value_type n;
    for (int i = 0; i < W; ++i) {
      if (i >= k) {
        clear_slot(n, i);
        continue;
      }
      set_slot_box(n, i, box_of(bin_[kids[i].node]));
      if (kids[i].leaf) {
        set_leaf_slot(n, i, range_begin(kids[i].node), range_end(kids[i].node), kids[i].area, tally);
      } else {
        n.child[i] = next++;
        n.count[i] = 0;
      }
    }
    nodes_[index] = n;
    return first_inner;
  }

  std::span<const BvhNode> bin_;
  int max_depth_;
  Nodes& nodes_;
};

}  // namespace

template <int W>
void WideBvh<W>::build_spatial(std::span<const Aabb> boxes, const PrimitiveOverlap& overlap,
                                     std::uint64_t max_refs) {
  BvhParams binary;
  binary.bins = params_.bins;
  binary.max_leaf_size = params_.max_leaf_size;
  binary.max_depth = 64;  // the wide depth limit is applied as the tree is collapsed
  binary.traversal_cost = params_.traversal_cost;
  binary.build_threads = 1;
  binary.spatial_split_budget = params_.spatial_split_budget;
  std::vector<BvhNode> nodes;
  build_spatial_split_bvh(boxes, binary, overlap, max_refs, nodes, prim_ids_);
  const BuildTally tally = Collapser<W, decltype(nodes_)>(nodes, params_.max_depth, nodes_).run();
  tally.write_to(stats_, half_area_of(nodes[0]), boxes.size());
}

template void WideBvh<4>::build_spatial(std::span<const Aabb>, const PrimitiveOverlap&, std::uint64_t);
template void WideBvh<8>::build_spatial(std::span<const Aabb>, const PrimitiveOverlap&, std::uint64_t);

}  // namespace accel
