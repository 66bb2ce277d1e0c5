// The sliding-midpoint rule (Maneewongvatana and Mount, "It's okay to be skinny, if your friends
// are fat", 1999): split the cell's longest axis at its midpoint; when every photon lies on one
// side, slide the plane to the nearest photon and give that photon to the empty side. Cells
// never become empty, and thin clusters are cut off quickly instead of being halved level by
// level. The tree is not balanced.

#include "bucket_builder.h"

#include <algorithm>

namespace photon {

BucketTree BucketTree::sliding_midpoint(std::span<const Photon> photons, int leaf_size) {
  using bucket_detail::Item;
  return bucket_detail::build_bucket_tree(
      photons, leaf_size,
      [](Item* items, std::uint32_t begin, std::uint32_t end, const accel::Aabb& cell) {
        const int axis = cell.longest_axis();
        const auto below = [axis](const Item& a, const Item& b) { return a.p[axis] < b.p[axis]; };
        float plane = cell.lo[axis] + 0.5f * (cell.hi[axis] - cell.lo[axis]);
        Item* mid = std::partition(items + begin, items + end,
                                   [&](const Item& it) { return it.p[axis] < plane; });
        if (mid == items + begin) {
          // Every photon at or above the plane: slide it down to the lowest, which goes below.
          std::swap(*std::min_element(items + begin, items + end, below), items[begin]);
          plane = items[begin].p[axis];
          mid = items + begin + 1;
        } else if (mid == items + end) {
          // Every photon below: slide it up to the highest, which goes above.
          std::swap(*std::max_element(items + begin, items + end, below), items[end - 1]);
          plane = items[end - 1].p[axis];
          mid = items + end - 1;
        }
        return bucket_detail::Split{axis, plane, std::uint32_t(mid - items)};
      });
}

}  // namespace photon
