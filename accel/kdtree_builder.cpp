// kd-tree construction, depth first over one work array of primitive ids: a cell's primitives
// are a segment of it; a split appends the lower and upper children's segments at the end, and
// the array is cut back when the cell is done, so the build makes no allocation per node.
// Nodes are written in pbrt-v3's order: an inner node, its lower subtree, its upper subtree.

#include "kdtree.h"

#include "accel.h"
#include "build_budget.h"
#include "kdtree_sah.h"

#include <algorithm>
#include <optional>

namespace accel {
namespace {

class KdTreeBuilder {
 public:
  KdTreeBuilder(std::span<const Aabb> boxes, const KdTreeParams& params, std::uint64_t budget,
                const PrimitiveOverlap& overlap, std::vector<KdNode>& nodes,
                std::vector<std::uint32_t>& prim_ids, std::vector<KdPrimRange>& inner_prims, BuildStats& stats)
      : boxes_(boxes),
        params_(params),
        overlap_(overlap),
        every_level_(params.placement == Placement::EveryLevel),
        budget_(budget, "kdtree",
                "lower max_depth or raise max_leaf_size, or use placement every_level"),
        nodes_(nodes),
        prim_ids_(prim_ids),
        inner_prims_(inner_prims),
        stats_(stats) {}

  void run(const Aabb& bounds) {
    const std::size_t n = boxes_.size();
    budget_.reserve_more(work_, n);
    for (std::uint32_t i = 0; i < n; ++i) work_.push_back(i);
    budget_.reserve_more(side_, n);
    side_.resize(n);
    if (params_.split == SplitRule::Sah) sah_.emplace(boxes_, params_, overlap_, budget_);
    const float root_area = bounds.half_area();
    inv_root_area_ = root_area > 0.0f ? 1.0 / double(root_area) : 0.0;
    build(0, bounds, 0, n, 0);

    sah_.reset();
    budget_.release(work_);
    budget_.release(side_);
    nodes_.shrink_to_fit();
    prim_ids_.shrink_to_fit();
    inner_prims_.shrink_to_fit();
    stats_.primitives = n;
    stats_.nodes = nodes_.size();
    stats_.prim_refs = prim_ids_.size();
    leaf_tally_.finish(stats_);
    stats_.memory_bytes = nodes_.size() * sizeof(KdNode) +
                          prim_ids_.size() * sizeof(std::uint32_t) +
                          inner_prims_.size() * sizeof(KdPrimRange);
  }

 private:
  /// Appends the node for `cell`, whose primitives are work_[begin, end), and its subtrees.
  void build(int depth, const Aabb& cell, std::size_t begin, std::size_t end, int bad_refines) {
    const std::uint32_t node = std::uint32_t(nodes_.size());
    if (node > KdNode::kMaxIndex)
      throw knobs::ConfigError("kdtree: more than 2^30 nodes; lower max_depth or raise max_leaf_size");
    budget_.reserve_more(nodes_, 1);
    nodes_.emplace_back();
    if (every_level_) {
      budget_.reserve_more(inner_prims_, 1);
      inner_prims_.emplace_back();
    }
    const std::size_t n = end - begin;
    const double area = inv_root_area_ > 0.0 ? double(cell.half_area()) * inv_root_area_
                                             : (depth == 0 ? 1.0 : 0.0);
    stats_.max_depth_reached = std::max(stats_.max_depth_reached, depth);
    if (n <= std::size_t(params_.max_leaf_size) || depth >= params_.max_depth) {
      make_leaf(node, begin, end, area);
      return;
    }

    KdSplit split;
    if (params_.split == SplitRule::Sah) {
      const std::span<const std::uint32_t> prims(work_.data() + begin, n);
      if (!sah_->find(cell, prims, bad_refines, split, side_.data())) {
        make_leaf(node, begin, end, area);
        return;
      }
    } else {
      split.axis = cell.longest_axis();
      split.position = 0.5f * (cell.lo[split.axis] + cell.hi[split.axis]);
      // Half-open sides: a box touching the plane goes to one side only, and a flat box lying
      // in it to the lower side.
      for (std::size_t i = begin; i < end; ++i) {
        const Aabb& b = boxes_[work_[i]];
        const bool above = b.hi[split.axis] > split.position;
        const bool below = b.lo[split.axis] < split.position || !above;
        side_[work_[i]] = std::uint8_t((below ? kBelow : 0) | (above ? kAbove : 0));
      }
    }

    // A box across the plane: keep the sides the primitive itself touches (both when it touches
    // neither: it touches the cell, so its box decides).
    Aabb below_cell = cell, above_cell = cell;
    below_cell.hi[split.axis] = split.position;
    above_cell.lo[split.axis] = split.position;
    if (overlap_.active())
      for (std::size_t i = begin; i < end; ++i) {
        std::uint8_t& s = side_[work_[i]];
        if (s != (kBelow | kAbove)) continue;
        const std::uint8_t kept = std::uint8_t((overlap_(work_[i], below_cell) ? kBelow : 0) |
                                               (overlap_(work_[i], above_cell) ? kAbove : 0));
        if (kept) s = kept;
      }

    // With every_level, straddlers stay in this node; everything else goes down.
    std::size_t n_below = 0, n_above = 0, own = 0;
    for (std::size_t i = begin; i < end; ++i) {
      std::uint8_t& s = side_[work_[i]];
      if (every_level_ && s == (kBelow | kAbove)) {
        s = 0;
        ++own;
      }
      n_below += (s & kBelow) != 0;
      n_above += (s & kAbove) != 0;
    }
    if (own) {
      inner_prims_[node] = {std::uint32_t(prim_ids_.size()), std::uint32_t(own)};
      budget_.reserve_more(prim_ids_, own);
      for (std::size_t i = begin; i < end; ++i)
        if (side_[work_[i]] == 0) prim_ids_.push_back(work_[i]);
    }
    if (own == n) {  // every primitive straddles: this node is a leaf holding them all
      inner_prims_[node] = {};
      nodes_[node] = KdNode::leaf(std::uint32_t(prim_ids_.size() - own), std::uint32_t(own));
      count_leaf(own, area);
      return;
    }

    const std::size_t base = work_.size();
    budget_.reserve_more(work_, n_below + n_above);
    work_.resize(base + n_below + n_above);
    std::size_t lo = base, hi = base + n_below;
    for (std::size_t i = begin; i < end; ++i) {
      const std::uint32_t p = work_[i];
      if (side_[p] & kBelow) work_[lo++] = p;
      if (side_[p] & kAbove) work_[hi++] = p;
      side_[p] = 0;
    }

    stats_.sah_cost += area * (1.0 + double(own));
    build(depth + 1, below_cell, base, base + n_below, bad_refines);
    nodes_[node] = KdNode::inner(split.axis, split.position, std::uint32_t(nodes_.size()));
    build(depth + 1, above_cell, base + n_below, base + n_below + n_above, bad_refines);
    work_.resize(base);
  }

  void make_leaf(std::uint32_t node, std::size_t begin, std::size_t end, double area) {
    const std::size_t n = end - begin;
    nodes_[node] = KdNode::leaf(std::uint32_t(prim_ids_.size()), std::uint32_t(n));
    budget_.reserve_more(prim_ids_, n);
    prim_ids_.insert(prim_ids_.end(), work_.begin() + std::ptrdiff_t(begin),
                     work_.begin() + std::ptrdiff_t(end));
    count_leaf(n, area);
  }

  void count_leaf(std::size_t prims, double area) { leaf_tally_.add(stats_, prims, area); }

  std::span<const Aabb> boxes_;
  const KdTreeParams& params_;
  const PrimitiveOverlap& overlap_;
  bool every_level_;
  BuildBudget budget_;
  std::vector<KdNode>& nodes_;
  std::vector<std::uint32_t>& prim_ids_;
  std::vector<KdPrimRange>& inner_prims_;
  BuildStats& stats_;
  std::vector<std::uint32_t> work_;  ///< Primitive ids of the cells on the current path.
  std::vector<std::uint8_t> side_;   ///< Per primitive id: kBelow | kAbove of the current split.
  std::optional<KdSahSplitter> sah_;
  double inv_root_area_ = 0.0;
  LeafTally leaf_tally_;
};

}  // namespace

void KdTree::build(std::span<const Aabb> boxes, std::uint64_t budget_bytes, const PrimitiveOverlap& overlap) {
  if (boxes.size() > KdNode::kMaxIndex)
    throw knobs::ConfigError("kdtree: at most 2^30 - 1 primitives");
  bounds_ = {};
  for (const Aabb& b : boxes) bounds_.grow(b);
  if (bounds_.is_empty()) bounds_ = {Vec3(0.0f), Vec3(0.0f)};
  stats_ = {};
  KdTreeBuilder(boxes, params_, budget_bytes, overlap, nodes_, prim_ids_, inner_prims_, stats_)
      .run(bounds_);
}

}  // namespace accel
