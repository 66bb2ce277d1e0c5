// Spatial-split BVH build (Stich et al. 2009), see spatial_split_builder.h.
//
// A node's references (a primitive id and a box around its part in the node) are searched twice:
// - object split: centroids binned along each axis, as the binned SAH builder does;
// - spatial split: the node's box cut into equal bins along each axis; a reference enters the bin
//   of its box's low face and exits the bin of its high face, and each bin grows by the box of
//   the primitive's part inside it. A plane between bins k - 1 and k sends left what entered
//   before it and right what exits after it, so a straddler counts on both sides.
// The spatial search runs only where the object split's children overlap by more than
// kMinOverlap of the root's area (the paper's alpha): elsewhere it cannot win and would cost a
// clip per bin per reference. A straddler of the chosen plane is cut in two unless keeping it
// whole on one side costs less ("reference unsplitting"), or the reference budget is spent.

#include "spatial_split_builder.h"

#include "binned_sah.h"

#include <algorithm>
#include <array>
#include <utility>

namespace accel {
namespace {

struct Ref {
  Aabb box;  ///< Around the primitive's part in the node that holds this reference.
  std::uint32_t id;
};

/// The paper's alpha: spatial splits are searched where the object split's children overlap by
/// more than this share of the root's half-area.
constexpr float kMinOverlap = 1e-5f;

Aabb intersection(const Aabb& a, const Aabb& b) { return {glm::max(a.lo, b.lo), glm::min(a.hi, b.hi)}; }

Aabb union_of(Aabb a, const Aabb& b) {
  a.grow(b);
  return a;
}

/// Equal bins over [lo, lo + extent) of one axis; the same function bins and partitions, so
/// both agree on every reference's side.
struct AxisBins {
  float lo = 0.0f, scale = 0.0f, width = 0.0f;
  int count = 0;
  AxisBins(float low, float extent, int bins)
      : lo(low), scale(float(bins) / extent), width(extent / float(bins)), count(bins) {}
  int of(float x) const { return std::clamp(int((x - lo) * scale), 0, count - 1); }
  /// Where bin k starts (k = count: the node's upper face is not needed, the node box bounds).
  float plane(int k) const { return lo + width * float(k); }
};

class SpatialSplitBuilder {
 public:
  SpatialSplitBuilder(const BvhParams& params, const PrimitiveOverlap& overlap, std::uint64_t max_refs,
                      std::vector<BvhNode>& nodes, std::vector<std::uint32_t>& prim_ids)
      : params_(params),
        bins_(std::clamp(params.bins, 2, BinnedSah::kMaxBins)),
        overlap_(overlap),
        max_refs_(max_refs),
        nodes_(nodes),
        prim_ids_(prim_ids) {}

  BuildTally run(std::span<const Aabb> boxes) {
    std::vector<Ref> refs(boxes.size());
    Aabb box;
    for (std::uint32_t i = 0; i < boxes.size(); ++i) {
      refs[i] = {boxes[i], i};
      box.grow(boxes[i]);
    }
    refs_ = refs.size();
    root_area_ = box.half_area();
    nodes_.assign(2, BvhNode{});  // the root, then the unused node that aligns sibling pairs
    prim_ids_.clear();
    prim_ids_.reserve(refs.size());
    BuildTally tally;
    build_node(0, std::move(refs), box, 0, tally);
    return tally;
  }

 private:
  struct Split {
    enum Kind { None, Object, Spatial } kind = None;
    int axis = -1;
    int bin = 0;  ///< Object: centroid bins [0, bin) go left; spatial: the plane before bin `bin`.
    float cost = kInfinity;
    Aabb left, right;  ///< The children's boxes the search priced.
    std::uint32_t left_count = 0, right_count = 0;
    Aabb centroids;  ///< Object: the box of the centroids its bins divide.
  };

  void build_node(std::uint32_t index, std::vector<Ref> refs, const Aabb& box, int depth, BuildTally& tally) {
    set_box(nodes_[index], box);
    tally.max_depth_reached = std::max(tally.max_depth_reached, depth);
    const std::uint32_t count = std::uint32_t(refs.size());
    const float area = box.half_area();
    if (count == 1 || depth >= params_.max_depth) return make_leaf(index, refs, area, tally);

    const float inv_area = area > 0.0f ? 1.0f / area : 0.0f;
    Split split = object_split(refs, inv_area);
    const bool overlapping = split.kind == Split::None ||
                             intersection(split.left, split.right).half_area() > kMinOverlap * root_area_;
    if (overlapping) {
      Split spatial = spatial_split(refs, box, inv_area);
      if (spatial.cost < split.cost) split = spatial;
    }
    const bool small = count <= std::uint32_t(params_.max_leaf_size);
    if (small && (split.kind == Split::None || float(count) <= split.cost)) return make_leaf(index, refs, area, tally);

    std::vector<Ref> left, right;
    if (split.kind == Split::Object) {
      partition_object(refs, split, left, right);
    } else if (split.kind == Split::Spatial) {
      partition_spatial(refs, box, split, left, right);
    }
    if (left.empty() || right.empty()) {  // no plane separates them: halves in their order
      left.assign(refs.begin(), refs.begin() + count / 2);
      right.assign(refs.begin() + count / 2, refs.end());
    }
    refs = {};  // the children's references replace the node's before the subtrees build

    const std::uint32_t first = std::uint32_t(nodes_.size());
    nodes_.resize(nodes_.size() + 2);
    nodes_[index].first = first;
    nodes_[index].count = 0;
    tally.sah += area;  // one traversal step (BuildStats::sah_cost's traversal cost is 1)
    const Aabb left_box = bounds(left), right_box = bounds(right);
    build_node(first, std::move(left), left_box, depth + 1, tally);
    build_node(first + 1, std::move(right), right_box, depth + 1, tally);
  }

  /// Binned SAH over the references' centroids, as BinnedSah::find prices it.
  Split object_split(const std::vector<Ref>& refs, float inv_area) const {
    Aabb centroids;
    for (const Ref& r : refs) centroids.grow(r.box.center());
    Split best;
    best.centroids = centroids;
    std::array<Aabb, BinnedSah::kMaxBins> bin_box;
    std::array<std::uint32_t, BinnedSah::kMaxBins> bin_count;
    std::array<float, BinnedSah::kMaxBins> right_cost;
    std::array<Aabb, BinnedSah::kMaxBins> right_box;
    for (int axis = 0; axis < 3; ++axis) {
      const float extent = centroids.hi[axis] - centroids.lo[axis];
      if (!(extent > 0.0f)) continue;
      const AxisBins bins(centroids.lo[axis], extent, bins_);
      std::fill_n(bin_box.begin(), bins_, Aabb{});
      std::fill_n(bin_count.begin(), bins_, 0u);
      for (const Ref& r : refs) {
        const int k = bins.of(r.box.center()[axis]);
        bin_box[k].grow(r.box);
        bin_count[k]++;
      }
      sweep(bin_box, bin_count, bin_count, right_box, right_cost, inv_area, Split::Object, axis, best);
    }
    return best;
  }

  /// Equal bins over the node's box along each axis, every straddler clipped into each bin it
  /// crosses.
  Split spatial_split(const std::vector<Ref>& refs, const Aabb& box, float inv_area) const {
    Split best;
    std::array<Aabb, BinnedSah::kMaxBins> bin_box;
    std::array<std::uint32_t, BinnedSah::kMaxBins> entries, exits;
    std::array<float, BinnedSah::kMaxBins> right_cost;
    std::array<Aabb, BinnedSah::kMaxBins> right_box;
    for (int axis = 0; axis < 3; ++axis) {
      const float extent = box.hi[axis] - box.lo[axis];
      if (!(extent > 0.0f)) continue;
      const AxisBins bins(box.lo[axis], extent, bins_);
      std::fill_n(bin_box.begin(), bins_, Aabb{});
      std::fill_n(entries.begin(), bins_, 0u);
      std::fill_n(exits.begin(), bins_, 0u);
      for (const Ref& r : refs) {
        const int first = bins.of(r.box.lo[axis]), last = bins.of(r.box.hi[axis]);
        entries[first]++;
        exits[last]++;
        if (first == last) {
          bin_box[first].grow(r.box);
          continue;
        }
        for (int k = first; k <= last; ++k) {
          Aabb cell = box;
          if (k > first) cell.lo[axis] = bins.plane(k);
          if (k < last) cell.hi[axis] = bins.plane(k + 1);
          const Aabb part = overlap_.part(r.id, r.box, cell);
          if (!part.is_empty()) bin_box[k].grow(part);
        }
      }
      sweep(bin_box, entries, exits, right_box, right_cost, inv_area, Split::Spatial, axis, best);
    }
    return best;
  }

  /// The SAH sweep shared by both searches: the left side of plane k holds `left_counts` of bins
  /// [0, k), the right side `right_counts` of bins [k, bins); the cheapest plane with references
  /// on both sides replaces `best` when it costs less.
  void sweep(const std::array<Aabb, BinnedSah::kMaxBins>& bin_box,
             const std::array<std::uint32_t, BinnedSah::kMaxBins>& left_counts,
             const std::array<std::uint32_t, BinnedSah::kMaxBins>& right_counts,
             std::array<Aabb, BinnedSah::kMaxBins>& right_box, std::array<float, BinnedSah::kMaxBins>& right_cost,
             float inv_area, Split::Kind kind, int axis, Split& best) const {
    std::array<std::uint32_t, BinnedSah::kMaxBins> right_n;
    Aabb acc;
    std::uint32_t n = 0;
    for (int k = bins_ - 1; k > 0; --k) {
      acc.grow(bin_box[k]);
      n += right_counts[k];
      right_box[k] = acc;
      right_n[k] = n;
      right_cost[k] = acc.half_area() * float(n);
    }
    acc = Aabb{};
    n = 0;
    for (int k = 1; k < bins_; ++k) {
      acc.grow(bin_box[k - 1]);
      n += left_counts[k - 1];
      if (n == 0 || right_n[k] == 0) continue;
      const float cost = params_.traversal_cost + (acc.half_area() * float(n) + right_cost[k]) * inv_area;
      if (cost < best.cost) best = {kind, axis, k, cost, acc, right_box[k], n, right_n[k], best.centroids};
    }
  }

  void partition_object(const std::vector<Ref>& refs, const Split& split, std::vector<Ref>& left,
                        std::vector<Ref>& right) const {
    const Aabb& centroids = split.centroids;
    const AxisBins bins(centroids.lo[split.axis], centroids.hi[split.axis] - centroids.lo[split.axis], bins_);
    left.reserve(split.left_count);
    right.reserve(split.right_count);
    for (const Ref& r : refs) (bins.of(r.box.center()[split.axis]) < split.bin ? left : right).push_back(r);
  }

  void partition_spatial(const std::vector<Ref>& refs, const Aabb& box, const Split& split,
                         std::vector<Ref>& left, std::vector<Ref>& right) {
    const int axis = split.axis;
    const AxisBins bins(box.lo[axis], box.hi[axis] - box.lo[axis], bins_);
    const float plane = bins.plane(split.bin);
    Aabb left_cell = box, right_cell = box;
    left_cell.hi[axis] = plane;
    right_cell.lo[axis] = plane;
    // The sides as the search priced them; unsplitting a reference moves it and its box.
    Aabb left_box = split.left, right_box = split.right;
    float left_n = float(split.left_count), right_n = float(split.right_count);
    left.reserve(split.left_count);
    right.reserve(split.right_count);
    for (const Ref& r : refs) {
      const int first = bins.of(r.box.lo[axis]), last = bins.of(r.box.hi[axis]);
      if (last < split.bin) {
        left.push_back(r);
      } else if (first >= split.bin) {
        right.push_back(r);
      } else {
        const Aabb l = overlap_.part(r.id, r.box, left_cell), rr = overlap_.part(r.id, r.box, right_cell);
        if (rr.is_empty()) {
          left.push_back({l.is_empty() ? r.box : l, r.id});
          continue;
        }
        if (l.is_empty()) {
          right.push_back({rr, r.id});
          continue;
        }
        const float split_cost = left_box.half_area() * left_n + right_box.half_area() * right_n;
        const float left_only = union_of(left_box, r.box).half_area() * left_n + right_box.half_area() * (right_n - 1.0f);
        const float right_only = left_box.half_area() * (left_n - 1.0f) + union_of(right_box, r.box).half_area() * right_n;
        const bool may_duplicate = refs_ < max_refs_;
        if (may_duplicate && split_cost <= left_only && split_cost <= right_only) {
          left.push_back({l, r.id});
          right.push_back({rr, r.id});
          ++refs_;
        } else if (left_only <= right_only) {
          left.push_back(r);
          left_box.grow(r.box);
          right_n -= 1.0f;
        } else {
          right.push_back(r);
          right_box.grow(r.box);
          left_n -= 1.0f;
        }
      }
    }
  }

  void make_leaf(std::uint32_t index, const std::vector<Ref>& refs, float area, BuildTally& tally) {
    nodes_[index].first = std::uint32_t(prim_ids_.size());
    nodes_[index].count = std::uint32_t(refs.size());
    for (const Ref& r : refs) prim_ids_.push_back(r.id);
    tally.leaves++;
    tally.max_leaf_prims = std::max<std::uint64_t>(tally.max_leaf_prims, refs.size());
    tally.sah += double(area) * double(refs.size());
  }

  static Aabb bounds(const std::vector<Ref>& refs) {
    Aabb b;
    for (const Ref& r : refs) b.grow(r.box);
    return b;
  }

  static void set_box(BvhNode& n, const Aabb& box) {
    for (int a = 0; a < 3; ++a) {
      n.lo[a] = box.lo[a];
      n.hi[a] = box.hi[a];
    }
  }

  const BvhParams& params_;
  const int bins_;
  const PrimitiveOverlap& overlap_;
  const std::uint64_t max_refs_;
  std::vector<BvhNode>& nodes_;
  std::vector<std::uint32_t>& prim_ids_;
  std::uint64_t refs_ = 0;  ///< References made so far, the node's included.
  float root_area_ = 0.0f;
};

}  // namespace

BuildTally build_spatial_split_bvh(std::span<const Aabb> boxes, const BvhParams& params,
                                   const PrimitiveOverlap& overlap, std::uint64_t max_refs,
                                   std::vector<BvhNode>& nodes, std::vector<std::uint32_t>& prim_ids) {
  SpatialSplitBuilder builder(params, overlap, max_refs, nodes, prim_ids);
  return builder.run(boxes);
}

}  // namespace accel
