// Octree construction, level by level: a level's cells are a list, their primitive ids segments
// of one array, and the next level is counted before it is written, so the build makes no
// allocation per node and checks the memory budget before an exploding level is stored.

#include "octree.h"

#include "accel.h"
#include "build_budget.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>

namespace accel {
namespace {

/// Children (as an 8-bit mask) of a cell split at `mid` that the box overlaps. Half-open, so a
/// box merely touching a mid-plane goes to one side only; a flat box lying in the plane goes to
/// the lower side.
std::uint8_t overlap_mask(const Aabb& b, const Vec3& mid) {
  static constexpr std::uint8_t kLower[3] = {0x55, 0x33, 0x0f};  // children with bit k clear
  std::uint8_t mask = 0xff;
  for (int a = 0; a < 3; ++a) {
    const bool upper = b.hi[a] > mid[a];
    const bool lower = b.lo[a] < mid[a] || !upper;
    mask &= std::uint8_t((lower ? kLower[a] : 0) | (upper ? ~kLower[a] : 0));
  }
  return mask;
}

class OctreeBuilder {
 public:
  OctreeBuilder(std::span<const Aabb> boxes, const OctreeParams& params, std::uint64_t budget,
                const PrimitiveOverlap& overlap, std::vector<OctreeNode>& nodes,
                std::vector<std::uint32_t>& prim_ids, BuildStats& stats)
      : boxes_(boxes),
        params_(params),
        overlap_(overlap),
        budget_(budget, "octree",
                "lower max_depth or raise max_leaf_size, or use placement every_level"),
        nodes_(nodes),
        prim_ids_(prim_ids),
        stats_(stats) {}

  void run(const Aabb& root_cell) {
    const std::size_t n = boxes_.size();
    budget_.reserve_more(refs_, n);
    for (std::uint32_t i = 0; i < n; ++i) refs_.push_back(i);
    budget_.reserve_more(level_, 1);
    level_.push_back({0, root_cell, 0, n});
    budget_.reserve_more(nodes_, 1);
    nodes_.emplace_back();
    const float root_area = root_cell.half_area();
    inv_root_area_ = root_area > 0.0f ? 1.0 / double(root_area) : 0.0;
    for (int depth = 0; !level_.empty(); ++depth) {
      stats_.max_depth_reached = depth;
      split_level(depth);
    }

    for (auto* v : {&refs_, &next_refs_}) budget_.release(*v);
    budget_.release(masks_);
    budget_.release(level_);
    budget_.release(next_level_);
    nodes_.shrink_to_fit();
    prim_ids_.shrink_to_fit();
    stats_.primitives = n;
    stats_.nodes = nodes_.size();
    stats_.prim_refs = prim_ids_.size();
    leaf_tally_.finish(stats_);
    stats_.memory_bytes =
        nodes_.size() * sizeof(OctreeNode) + prim_ids_.size() * sizeof(std::uint32_t);
  }

 private:
  /// A cell of the level being built: its node and its primitives, refs_[begin, end).
  struct Cell {
    std::uint32_t node;
    Aabb box;
    std::size_t begin, end;
  };

  /// Turns every cell of level_ (at `depth`) into a leaf or an inner node, and gathers the
  /// next level. The build goes level by level so that the next level's size is known, and
  /// checked against the budget, before any of it is written: a subdivision that explodes
  /// (about 8x more references per level) stops after building an eighth of the budget.
  void split_level(int depth) {
    // Pass 1: leaves are stored; cells to split get their children's sizes counted.
    const bool every_level = params_.placement == Placement::EveryLevel;
    budget_.reserve_more(masks_, refs_.size());
    masks_.resize(refs_.size());
    std::size_t next_refs = 0, next_cells = 0;
    for (Cell& cell : level_) {
      const std::size_t n = cell.end - cell.begin;
      const double area = area_of(cell.box, depth);
      OctreeNode& node = nodes_[cell.node];
      if (n <= std::size_t(params_.max_leaf_size) || depth >= params_.max_depth) {
        store(node, cell.begin, cell.end, [](std::uint8_t) { return true; });
        make_leaf(n, area);
        cell.end = cell.begin;  // nothing goes down
        continue;
      }
      const Vec3 mid = cell_mid(cell.box);
      std::uint8_t child_mask = 0;
      std::size_t own = 0;
      for (std::size_t i = cell.begin; i < cell.end; ++i) {
        std::uint8_t m = overlap_mask(boxes_[refs_[i]], mid);
        // A box over several children: keep the children the primitive itself touches.
        if (overlap_.active() && std::popcount(m) > 1) m = touched(refs_[i], m, cell.box, mid);
        if (every_level && std::popcount(m) > 1) {
          m = 0;
          ++own;
        }
        masks_[i] = m;
        child_mask |= m;
        next_refs += unsigned(std::popcount(m));
      }
      store(node, cell.begin, cell.end, [](std::uint8_t m) { return m == 0; });  // straddlers
      node.child_mask = child_mask;
      next_cells += unsigned(std::popcount(child_mask));
      if (child_mask == 0) {  // every primitive straddles: this cell is a leaf after all
        make_leaf(own, area);
        cell.end = cell.begin;
      } else {
        stats_.sah_cost += area * (1.0 + double(own));
      }
    }

    // Pass 2: the next level, within the budget, children of a cell contiguous.
    next_refs_.clear();
    next_level_.clear();
    budget_.reserve_more(next_refs_, next_refs);
    budget_.reserve_more(next_level_, next_cells);
    budget_.reserve_more(nodes_, next_cells);
    for (const Cell& cell : level_) {
      OctreeNode& node = nodes_[cell.node];
      if (cell.end == cell.begin || node.child_mask == 0) continue;
      node.first_child = std::uint32_t(nodes_.size());
      const Vec3 mid = cell_mid(cell.box);
      for (unsigned m = node.child_mask; m != 0; m &= m - 1) {
        const unsigned c = unsigned(std::countr_zero(m));
        const std::size_t begin = next_refs_.size();
        for (std::size_t i = cell.begin; i < cell.end; ++i)
          if ((masks_[i] >> c) & 1u) next_refs_.push_back(refs_[i]);
        next_level_.push_back({std::uint32_t(nodes_.size()), child_cell(cell.box, mid, c), begin,
                               next_refs_.size()});
        nodes_.emplace_back();
      }
    }
    refs_.swap(next_refs_);
    level_.swap(next_level_);
  }

  /// Appends to prim_ids_ the primitives of refs_[begin, end) whose mask passes `keep`, as the
  /// node's own list.
  template <class Keep>
  void store(OctreeNode& node, std::size_t begin, std::size_t end, Keep keep) {
    node.prim_begin = std::uint32_t(prim_ids_.size());
    std::size_t count = 0;
    for (std::size_t i = begin; i < end; ++i) count += keep(masks_[i]);
    budget_.reserve_more(prim_ids_, count);
    for (std::size_t i = begin; i < end; ++i)
      if (keep(masks_[i])) prim_ids_.push_back(refs_[i]);
    node.prim_count = std::uint32_t(count);
  }

  /// The children of `mask` (of `box` split at `mid`) that primitive `id` touches; all of
  /// `mask` when it touches none (it touches the cell: keep it where its box says).
  std::uint8_t touched(std::uint32_t id, std::uint8_t mask, const Aabb& box, const Vec3& mid) const {
    std::uint8_t kept = 0;
    for (unsigned m = mask; m != 0; m &= m - 1) {
      const unsigned c = unsigned(std::countr_zero(m));
      if (overlap_(id, child_cell(box, mid, c))) kept |= std::uint8_t(1u << c);
    }
    return kept ? kept : mask;
  }

  double area_of(const Aabb& box, int depth) const {
    if (inv_root_area_ > 0.0) return double(box.half_area()) * inv_root_area_;
    return depth == 0 ? 1.0 : 0.0;  // a point-sized scene: only the root counts
  }

  void make_leaf(std::size_t prims, double area) { leaf_tally_.add(stats_, prims, area); }

  std::span<const Aabb> boxes_;
  const OctreeParams& params_;
  const PrimitiveOverlap& overlap_;
  BuildBudget budget_;
  std::vector<OctreeNode>& nodes_;
  std::vector<std::uint32_t>& prim_ids_;
  BuildStats& stats_;
  std::vector<Cell> level_, next_level_;         ///< Cells of this level and of the next.
  std::vector<std::uint32_t> refs_, next_refs_;  ///< Their primitive ids.
  std::vector<std::uint8_t> masks_;              ///< Per entry of refs_: children it goes to.
  double inv_root_area_ = 0.0;
  LeafTally leaf_tally_;
};

/// A cube around every box (the root cell), or a point at the origin when there is none.
Aabb root_cube(std::span<const Aabb> boxes) {
  Aabb bounds;
  for (const Aabb& b : boxes) bounds.grow(b);
  if (bounds.is_empty()) return {Vec3(0.0f), Vec3(0.0f)};
  const Vec3 e = bounds.extent();
  const Vec3 half(0.5f * std::max({e.x, e.y, e.z}));
  const Vec3 c = bounds.center();
  // Rounding may leave c +- half an ulp inside the bounds; the cube is widened to contain them.
  return {glm::min(c - half, bounds.lo), glm::max(c + half, bounds.hi)};
}

}  // namespace

void Octree::build(std::span<const Aabb> boxes, std::uint64_t budget_bytes, const PrimitiveOverlap& overlap) {
  if (boxes.size() >= std::numeric_limits<std::uint32_t>::max())
    throw knobs::ConfigError("octree: at most 2^32 - 2 primitives");
  root_cell_ = root_cube(boxes);
  stats_ = {};
  OctreeBuilder(boxes, params_, budget_bytes, overlap, nodes_, prim_ids_, stats_).run(root_cell_);
}

}  // namespace accel
