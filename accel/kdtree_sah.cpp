#include "kdtree_sah.h"

#include <algorithm>

namespace accel {

KdSahSplitter::KdSahSplitter(std::span<const Aabb> boxes, const KdTreeParams& params,
                             const PrimitiveOverlap& overlap, BuildBudget& budget)
    : boxes_(boxes),
      params_(params),
      overlap_(overlap),
      clipped_(params.split_candidates == SplitCandidates::Clipped && overlap.clip != nullptr) {
  if (clipped_) {
    budget.reserve_more(parts_, boxes.size());
    parts_.resize(boxes.size());
  }
  for (std::vector<Edge>& e : edges_) {
    budget.reserve_more(e, 2 * boxes.size());
    e.resize(2 * boxes.size());
  }
}

bool KdSahSplitter::find(const Aabb& cell, std::span<const std::uint32_t> prims,
                         int& bad_refines, KdSplit& split, std::uint8_t* side) {
  const std::size_t n = prims.size();
  const float total_area = cell.half_area();
  if (!(total_area > 0.0f)) return false;
  const float inv_total = 1.0f / total_area;
  const Vec3 d = cell.extent();
  const bool every_level = params_.placement == Placement::EveryLevel;
  const float leaf_cost = params_.intersection_cost * float(n);
  if (clipped_)
    for (std::size_t i = 0; i < n; ++i) parts_[i] = overlap_.part(prims[i], boxes_[prims[i]], cell);
  const auto box_of = [&](std::size_t i) -> const Aabb& { return clipped_ ? parts_[i] : boxes_[prims[i]]; };

  int best_axis = -1;
  std::size_t best_offset = 0;
  float best_cost = kInfinity;
  int axis = cell.longest_axis();
  for (int retries = 0; retries < 3 && best_axis == -1; ++retries, axis = (axis + 1) % 3) {
    Edge* edges = edges_[axis].data();
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t p = prims[i];
      edges[2 * i] = {box_of(i).lo[axis], p << 1};
      edges[2 * i + 1] = {box_of(i).hi[axis], (p << 1) | 1u};
    }
    // At equal coordinates lower faces come first, as in pbrt-v3.
    std::sort(edges, edges + 2 * n, [](const Edge& a, const Edge& b) {
      return a.t < b.t || (a.t == b.t && (a.prim_end & 1u) < (b.prim_end & 1u));
    });

    // Sweep: at edge i, n_below primitives start before it and n_above end after it.
    const int o0 = (axis + 1) % 3, o1 = (axis + 2) % 3;
    const float cap = d[o0] * d[o1], rim = d[o0] + d[o1];
    std::size_t n_below = 0, n_above = n;
    for (std::size_t i = 0; i < 2 * n; ++i) {
      const bool is_end = edges[i].prim_end & 1u;
      if (is_end) --n_above;
      const float t = edges[i].t;
      if (t > cell.lo[axis] && t < cell.hi[axis]) {
        const float p_below = (cap + (t - cell.lo[axis]) * rim) * inv_total;
        const float p_above = (cap + (cell.hi[axis] - t) * rim) * inv_total;
        // With every_level the straddlers stay in this node and are tested on every visit.
        std::size_t nb = n_below, na = n_above, own = 0;
        if (every_level) {
          nb = n - n_above;
          na = n - n_below;
          own = n_below + n_above - n;
        }
        // The bonus is for a child with nothing in it: with every_level a side with no
        // primitive of its own but straddlers at this node is not empty space (otherwise the
        // search peels one straddler per level off the cell, each time with the bonus).
        const float bonus = own == 0 && (nb == 0 || na == 0) ? params_.empty_bonus : 0.0f;
        const float cost =
            params_.traversal_cost +
            params_.intersection_cost *
                (float(own) + (1.0f - bonus) * (p_below * float(nb) + p_above * float(na)));
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_offset = i;
        }
      }
      if (!is_end) ++n_below;
    }
  }

  if (best_cost > leaf_cost) ++bad_refines;
  if ((best_cost > 4.0f * leaf_cost && n < 16) || best_axis == -1 || bad_refines == 3)
    return false;

  const Edge* edges = edges_[best_axis].data();
  for (std::size_t i = 0; i < best_offset; ++i)
    if (!(edges[i].prim_end & 1u)) side[edges[i].prim_end >> 1] |= kBelow;
  for (std::size_t i = best_offset + 1; i < 2 * n; ++i)
    if (edges[i].prim_end & 1u) side[edges[i].prim_end >> 1] |= kAbove;
  split = {best_axis, edges[best_offset].t};
  return true;
}

}  // namespace accel
