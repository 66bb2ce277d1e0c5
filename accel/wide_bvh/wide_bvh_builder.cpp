// Direct binned-SAH build of the wide BVHs: a node's range takes its SAH split, then the node
// keeps splitting its child with the largest surface area (leaves excepted) until it has W
// children, which is how a binary SAH tree is collapsed into a wide one, without storing the
// binary tree. Children are allocated together, depth first.

#include "wide_bvh.h"

#include "accel/accel.h"
#include "accel/binned_sah.h"

#include <algorithm>
#include <chrono>
#include <string>

namespace accel {

template <int W>
const knobs::KnobTable<WideBvhParams<W>>& WideBvhParams<W>::knobs() {
  using P = WideBvhParams<W>;
  using K = knobs::Knob<P>;
  static const knobs::KnobTable<P> table(
      WideBvhWidth<W>::kName,
      {K::integer("bins", &P::bins, 8, 256, "bins per axis",
                  "Centroid bins per axis the SAH evaluates; more bins approach a full sweep.")
           .probes({8, 256}),
       K::integer("max_leaf_size", &P::max_leaf_size, 1, 255, "primitives",
                  "A range holding more primitives is always split; at or below it the SAH decides.")
           .shorthand("--leaf-size")
           .crossed()
           .probes({1, 2, 4, 8, 16}),
       K::integer("max_depth", &P::max_depth, 0, 64, "levels",
                  "Deepest level of wide nodes (root = 0): a range there is a leaf whatever it holds.")
           .shorthand()
           .crossed()
           .probes({0, 1, 2, 3, 5, 8, 12, 20}),
       K::number("traversal_cost", &P::traversal_cost, 0.0, 1000.0, "primitive tests",
                 "Cost of one node step relative to one primitive test (SAH C_trav / C_isect).")
           .probes({0.1, 1000.0})});
  return table;
}

namespace {

template <int W>
class WideBuilder {
 public:
  using Node = WideNode<W>;
  using Nodes = std::vector<Node, CacheLineAllocator<Node>>;

  WideBuilder(std::span<const Aabb> boxes, const WideBvhParams<W>& params, Nodes& nodes,
              std::vector<std::uint32_t>& ids, BuildStats& stats)
      : params_(params), nodes_(nodes), ids_(ids), stats_(stats), sah_(boxes, params.bins, params.traversal_cost) {}

  /// Builds the nodes and leaves the primitive ids in leaf order.
  void run() {
    const auto n = std::uint32_t(ids_.size());
    const Range root = make_range(0, n, 0, sah_.bounds(0, n));
    root_area_ = root.area;
    nodes_.push_back({});
    if (root.leaf) {
      // One leaf holds everything: the root node has that leaf as its only child.
      Range kids[W] = {root};
      fill_node(0, kids, 1);
    } else {
      build_node(0, root, 0);
    }
    sah_.copy_ids(ids_);
  }

  /// Sum of the SAH terms (traversal cost 1, intersection cost 1) before normalisation.
  double sah_sum() const { return sah_sum_; }
  float root_area() const { return root_area_; }

 private:
  /// A range of ids, its bounds, and whether it becomes a leaf (else its split).
  struct Range {
    std::uint32_t begin = 0, end = 0;
    Aabb box, centroids;
    float area = 0.0f;
    int depth = 0;
    bool leaf = true;
    BinnedSah::Split split;
  };

  Range make_range(std::uint32_t begin, std::uint32_t end, int depth, const BinnedSah::Bounds& bounds) {
    Range r;
    r.begin = begin;
    r.end = end;
    r.depth = depth;
    r.box = bounds.box;
    r.centroids = bounds.centroids;
    r.area = r.box.half_area();
    const std::uint32_t count = end - begin;
    stats_.max_depth_reached = std::max(stats_.max_depth_reached, depth);
    if (count <= 1 || depth >= params_.max_depth) return r;
    r.split = sah_.find(begin, end, r.centroids, r.area);
    const bool small = count <= std::uint32_t(params_.max_leaf_size);
    r.leaf = small && (r.split.axis < 0 || float(count) <= r.split.cost);
    return r;
  }

  /// Splits `r` (not a leaf) into its two halves, at r.depth.
  void split(const Range& r, Range& left, Range& right) {
    BinnedSah::Bounds left_bounds, right_bounds;
    const std::uint32_t mid = sah_.partition(r.begin, r.end, r.centroids, r.split, left_bounds, right_bounds);
    left = make_range(r.begin, mid, r.depth, left_bounds);
    right = make_range(mid, r.end, r.depth, right_bounds);
  }

  /// Fills node `index` (a range that is not a leaf, at `depth`) and its subtree.
  void build_node(std::uint32_t index, const Range& r, int depth) {
    Range kids[W];
    Range whole = r;
    whole.depth = depth + 1;
    split(whole, kids[0], kids[1]);
    int k = 2;
    while (k < W) {
      int widest = -1;
      for (int i = 0; i < k; ++i)
        if (!kids[i].leaf && (widest < 0 || kids[i].area > kids[widest].area)) widest = i;
      if (widest < 0) break;
      const Range opened = kids[widest];
      split(opened, kids[widest], kids[k]);
      ++k;
    }
    sah_sum_ += double(r.area);  // one node step
    const std::uint32_t first_inner = fill_node(index, kids, k);
    std::uint32_t next = first_inner;
    for (int i = 0; i < k; ++i)
      if (!kids[i].leaf) build_node(next++, kids[i], depth + 1);
  }

  /// Writes node `index` from its k children; inner children get consecutive new nodes.
  /// Returns the index of the first of them.
  std::uint32_t fill_node(std::uint32_t index, const Range* kids, int k) {
    const auto first_inner = std::uint32_t(nodes_.size());
    std::uint32_t next = first_inner;
    Node n;
    for (int i = 0; i < W; ++i) {
      if (i >= k) {
        for (int a = 0; a < 3; ++a) {
          n.planes[2 * a][i] = kInfinity;
          n.planes[2 * a + 1][i] = -kInfinity;
        }
        n.child[i] = 0;
        n.count[i] = 0;
        continue;
      }
      const Range& c = kids[i];
      for (int a = 0; a < 3; ++a) {
        const float pad = box_pad(c.box.lo[a], c.box.hi[a]);
        n.planes[2 * a][i] = c.box.lo[a] - pad;
        n.planes[2 * a + 1][i] = c.box.hi[a] + pad;
      }
      if (c.leaf) {
        n.child[i] = c.begin;
        n.count[i] = c.end - c.begin;
        stats_.leaves++;
        stats_.max_leaf_prims = std::max<std::uint64_t>(stats_.max_leaf_prims, c.end - c.begin);
        sah_sum_ += double(c.area) * double(c.end - c.begin);
      } else {
        n.child[i] = next++;
        n.count[i] = 0;
      }
    }
    nodes_[index] = n;
    nodes_.resize(next);
    return first_inner;
  }

  const WideBvhParams<W>& params_;
  Nodes& nodes_;
  std::vector<std::uint32_t>& ids_;
  BuildStats& stats_;
  BinnedSah sah_;
  double sah_sum_ = 0.0;
  float root_area_ = 0.0f;
};

}  // namespace

template <int W>
WideBvh<W>::WideBvh(std::span<const Aabb> boxes, const Params& params, const BuildLimits& limits) : params_(params) {
  Params::knobs().validate(params_);
  build(boxes, memory_budget_bytes(limits));
}

template <int W>
WideBvh<W>::WideBvh(std::span<const Aabb> boxes, const Params& params) : WideBvh(boxes, params, BuildLimits{}) {}

template <int W>
void WideBvh<W>::build(std::span<const Aabb> boxes, std::uint64_t budget_bytes) {
  const auto start = std::chrono::steady_clock::now();
  const std::uint64_t n = boxes.size();
  // Every inner node has at least two children, so there are fewer inner nodes than
  // primitives; the builder also holds one reference per primitive while it runs.
  // The primitives' padded boxes in leaf order take 6 floats each.
  const std::uint64_t bytes = std::max<std::uint64_t>(n, 1) * sizeof(Node) +
                              n * (sizeof(std::uint32_t) + BinnedSah::kBytesPerPrimitive + 6 * sizeof(float));
  if (bytes > budget_bytes)
    throw knobs::ConfigError(std::string(kName) + ": " + std::to_string(n) + " primitives need up to " + std::to_string(bytes) +
                      " bytes, over the memory budget of " + std::to_string(budget_bytes) +
                      " bytes (raise --max-memory)");
  nodes_.clear();
  prim_ids_.resize(n);  // the builder writes them in leaf order (BinnedSah::copy_ids)
  spheres_ = {};
  leaf_boxes_.clear();
  stats_ = {};
  stats_.primitives = n;
  stats_.prim_refs = n;
  if (n > 0) {
    WideBuilder<W> builder(boxes, params_, nodes_, prim_ids_, stats_);
    builder.run();
    // Normalised by the root's area; a flat or point-like root (area 0) costs its leaf tests.
    stats_.sah_cost = builder.root_area() > 0.0f ? builder.sah_sum() / double(builder.root_area()) : double(n);
  }
  nodes_.shrink_to_fit();
  leaf_boxes_.build(prim_ids_, boxes);
  stats_.nodes = nodes_.size();
  stats_.mean_leaf_prims = stats_.leaves ? double(n) / double(stats_.leaves) : 0.0;
  stats_.memory_bytes = memory_bytes();
  stats_.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

template struct WideBvhParams<4>;
template struct WideBvhParams<8>;
template class WideBvh<4>;
template class WideBvh<8>;

}  // namespace accel
