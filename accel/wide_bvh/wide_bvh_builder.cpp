// Direct binned-SAH build of the wide BVHs: a node's range takes its SAH split, then the node
// keeps splitting its child with the largest surface area (leaves excepted) until it has W
// children, which is how a binary SAH tree is collapsed into a wide one, without storing the
// binary tree. Children are allocated together, depth first. Large ranges build their inner
// children as parallel tasks (build_tasks.h); the tree is the same at any thread count.

#include "wide_bvh.h"
#include "wide_node_fill.h"

#include "accel/accel.h"
#include "accel/binned_sah.h"
#include "accel/build_tasks.h"
#include "accel/build_threads.h"
#include "accel/spatial_split_builder.h"

#include <tbb/parallel_for.h>

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
           .probes({0.1, 1000.0}),
       K::integer(kBuildThreadsKnob, &P::build_threads, 0, 1024, "threads",
                  "Threads the build may use (0 = every core); the tree is the same at any count.")
           .probes({2}),
       K::number("spatial_split_budget", &P::spatial_split_budget, 0.0, 4.0, "references per primitive",
                 "Extra references spatial splits (SBVH) may add per primitive; 0: none. Builds on one thread.")
           .probes({0.25, 4.0})});
  return table;
}

namespace {

template <int W>
class WideBuilder {
 public:
  using Node = WideNode<W>;
  using Slabs = NodeSlabs<Node>;

  /// Every inner node has at least two children, so a subtree over m primitives has fewer than m
  /// inner nodes: `node_capacity` = max(n, 1) + 1 holds any tree over n.
  WideBuilder(std::span<const Aabb> boxes, const WideBvhParams<W>& params, std::uint64_t node_capacity)
      : params_(params), sah_(boxes, params.bins, params.traversal_cost), slabs_(node_capacity) {}

  /// Builds the nodes over n primitives and returns what it counted.
  BuildTally run(std::uint32_t n) {
    BuildTally tally;
    const Range root = make_range(0, n, 0, sah_.bounds(0, n), tally);
    root_area_ = root.area;
    typename Slabs::Cursor c = slabs_.whole();
    slabs_.allocate(c, 1);
    if (root.leaf) {
      // One leaf holds everything: the root node has that leaf as its only child.
      Range kids[W] = {root};
      fill_node(c, 0, kids, 1, tally);
    } else {
      build_node(c, 0, root, 0, tally);
    }
    slabs_.close_run(c);
    return tally;
  }

  template <class Nodes>
  void compact(Nodes& nodes) {
    slabs_.compact(nodes, [](Node& node, const auto& renumber) {
      for (int i = 0; i < W; ++i)
        if (node.count[i] == 0) node.child[i] = renumber(node.child[i]);
    });
  }

  void copy_ids(std::vector<std::uint32_t>& ids) const { sah_.copy_ids(ids); }
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

  Range make_range(std::uint32_t begin, std::uint32_t end, int depth, const BinnedSah::Bounds& bounds, BuildTally& tally) {
    Range r;
    r.begin = begin;
    r.end = end;
    r.depth = depth;
    r.box = bounds.box;
    r.centroids = bounds.centroids;
    r.area = r.box.half_area();
    const std::uint32_t count = end - begin;
    tally.max_depth_reached = std::max(tally.max_depth_reached, depth);
    if (count <= 1 || depth >= params_.max_depth) return r;
    r.split = sah_.find(begin, end, r.centroids, r.area);
    const bool small = count <= std::uint32_t(params_.max_leaf_size);
    r.leaf = small && (r.split.axis < 0 || float(count) <= r.split.cost);
    return r;
  }

  /// Splits `r` (not a leaf) into its two halves, at r.depth.
  void split(const Range& r, Range& left, Range& right, BuildTally& tally) {
    BinnedSah::Bounds left_bounds, right_bounds;
    const std::uint32_t mid = sah_.partition(r.begin, r.end, r.centroids, r.split, left_bounds, right_bounds);
    left = make_range(r.begin, mid, r.depth, left_bounds, tally);
    right = make_range(mid, r.end, r.depth, right_bounds, tally);
  }

  /// Fills node `index` (a range that is not a leaf, at `depth`) and its subtree.
  void build_node(typename Slabs::Cursor& c, std::uint32_t index, const Range& r, int depth, BuildTally& tally) {
    Range kids[W];
    Range whole = r;
    whole.depth = depth + 1;
    split(whole, kids[0], kids[1], tally);
    int k = 2;
    while (k < W) {
      const int widest = widest_inner_child(kids, k);
      if (widest < 0) break;
      const Range opened = kids[widest];
      split(opened, kids[widest], kids[k], tally);
      ++k;
    }
    tally.sah += double(r.area);  // one node step
    const std::uint32_t first_inner = fill_node(c, index, kids, k, tally);
    if (r.end - r.begin < kForkPrims) {
      std::uint32_t next = first_inner;
      for (int i = 0; i < k; ++i)
        if (!kids[i].leaf) build_node(c, next++, kids[i], depth + 1, tally);
      return;
    }
    // Each inner child's subtree in a slab of its own, built as a task.
    slabs_.close_run(c);
    struct Task {
      int kid;
      std::uint32_t index;
      typename Slabs::Cursor cursor;
      BuildTally tally;
    };
    Task tasks[W];
    int count = 0;
    for (int i = 0; i < k; ++i) {
      if (kids[i].leaf) continue;
      // An inner child over m >= 2 primitives has at most m - 2 inner descendants (fewer than m
      // inner nodes, itself included), so the slabs of all children fit this node's own bound.
      tasks[count] = {i, first_inner + std::uint32_t(count), slabs_.carve(c, kids[i].end - kids[i].begin - 2), {}};
      ++count;
    }
    tbb::parallel_for(0, count, [&](int t) {
      Task& task = tasks[t];
      build_node(task.cursor, task.index, kids[task.kid], depth + 1, task.tally);
      slabs_.close_run(task.cursor);
    });
    for (int t = 0; t < count; ++t) tally.merge(tasks[t].tally);
  }

  /// Writes node `index` from its k children; inner children get consecutive new nodes.
  /// Returns the index of the first of them.
  std::uint32_t fill_node(typename Slabs::Cursor& c, std::uint32_t index, const Range* kids, int k, BuildTally& tally) {
    int inner = 0;
    for (int i = 0; i < k; ++i) inner += kids[i].leaf ? 0 : 1;
    const std::uint32_t first_inner = slabs_.allocate(c, std::uint32_t(inner));
    std::uint32_t next = first_inner;
    Node n;
    for (int i = 0; i < W; ++i) {
      if (i >= k) {
        clear_slot(n, i);
        continue;
      }
      const Range& kid = kids[i];
      set_slot_box(n, i, kid.box);
      if (kid.leaf) {
        set_leaf_slot(n, i, kid.begin, kid.end, kid.area, tally);
      } else {
        n.child[i] = next++;
        n.count[i] = 0;
      }
    }
    slabs_[index] = n;
    return first_inner;
  }

  const WideBvhParams<W>& params_;
  BinnedSah sah_;
  Slabs slabs_;
  float root_area_ = 0.0f;
};

}  // namespace

template <int W>
WideBvh<W>::WideBvh(std::span<const Aabb> boxes, const Params& params, const BuildLimits& limits) : params_(params) {
  Params::knobs().validate(params_);
  build(boxes, memory_budget_bytes(limits), !limits.shapes_follow, limits.overlap);
}

template <int W>
WideBvh<W>::WideBvh(std::span<const Aabb> boxes, const Params& params) : WideBvh(boxes, params, BuildLimits{}) {}

template <int W>
void WideBvh<W>::build(std::span<const Aabb> boxes, std::uint64_t budget_bytes, bool with_leaf_boxes,
                       const PrimitiveOverlap& overlap) {
  const auto start = std::chrono::steady_clock::now();
  const std::uint64_t n = boxes.size();
  const bool spatial = params_.spatial_split_budget > 0.0f;
  // Spatial splits may reference a primitive from several leaves, up to the budget.
  const std::uint64_t refs = spatial_split_max_refs(n, params_.spatial_split_budget);
  // Every inner node has at least two children, so there are fewer inner nodes than
  // references; the builder also holds one reference per primitive while it runs (the spatial
  // one its binary tree too, 2r nodes, and a box and an id per reference, the node's and its
  // children's). The primitives' padded boxes in leaf order take 6 floats each.
  const std::uint64_t scratch = spatial ? 2 * sizeof(BvhNode) + 2 * sizeof(Aabb) + 8 : BinnedSah::kBytesPerPrimitive;
  const std::uint64_t bytes = std::max<std::uint64_t>(refs, 1) * sizeof(Node) +
                              refs * (sizeof(std::uint32_t) + scratch + 6 * sizeof(float));
  if (bytes > budget_bytes)
    throw knobs::ConfigError(std::string(kName) + ": " + std::to_string(n) + " primitives need up to " + std::to_string(bytes) +
                      " bytes, over the memory budget of " + std::to_string(budget_bytes) +
                      " bytes (raise --max-memory)");
  nodes_.clear();
  prim_ids_.clear();
  spheres_ = {};
  leaf_boxes_.clear();
  stats_ = {};
  stats_.primitives = n;
  if (n > 0 && spatial) {
    build_spatial(boxes, overlap, refs);
  } else if (n > 0) {
    prim_ids_.resize(n);  // the builder writes them in leaf order (BinnedSah::copy_ids)
    run_with_build_threads(params_.build_threads, [&] {
      WideBuilder<W> builder(boxes, params_, std::max<std::uint64_t>(n, 1) + 1);
      const BuildTally tally = builder.run(std::uint32_t(n));
      builder.compact(nodes_);
      builder.copy_ids(prim_ids_);
      tally.write_to(stats_, builder.root_area(), n);
    });
  }
  nodes_.shrink_to_fit();
  prim_ids_.shrink_to_fit();
  stats_.prim_refs = prim_ids_.size();
  if (with_leaf_boxes) run_with_build_threads(params_.build_threads, [&] { leaf_boxes_.build(prim_ids_, boxes); });
  stats_.nodes = nodes_.size();
  stats_.mean_leaf_prims = stats_.leaves ? double(prim_ids_.size()) / double(stats_.leaves) : 0.0;
  stats_.memory_bytes = memory_bytes();
  stats_.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

template <int W>
void WideBvh<W>::attach_triangles(std::span<const TriangleShape> triangles) {
  stats_.memory_bytes -= leaf_boxes_.memory_bytes();
  leaf_boxes_.clear();  // triangle leaves test the triangles themselves
  const std::vector<LeafRange> leaves = leaf_ranges();
  run_with_build_threads(params_.build_threads, [&] {
    attach_leaf_shapes(kName, "triangles", triangles, triangles_, stats_,
                       [&](TriangleSoA& soa) { soa.build(prim_ids_, leaves, triangles); });
  });
}

template struct WideBvhParams<4>;
template struct WideBvhParams<8>;
template class WideBvh<4>;
template class WideBvh<8>;

}  // namespace accel
