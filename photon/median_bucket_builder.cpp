// The median rule with leaf buckets: split the cell's longest axis at the median photon, as the
// paper's balanced tree does, but keep photons in leaves of up to leaf_size. Against the
// sliding-midpoint tree, which has the same nodes, leaves and search, it measures balancing
// alone; against the balanced heap it measures the layout.

#include "bucket_builder.h"

#include <algorithm>

namespace photon {

BucketTree BucketTree::median(std::span<const Photon> photons, int leaf_size) {
  using bucket_detail::Item;
  return bucket_detail::build_bucket_tree(
      photons, leaf_size,
      [](Item* items, std::uint32_t begin, std::uint32_t end, const accel::Aabb& cell) {
        const int axis = cell.longest_axis();
        const std::uint32_t mid = begin + (end - begin) / 2;
        std::nth_element(items + begin, items + mid, items + end,
                         [axis](const Item& a, const Item& b) { return a.p[axis] < b.p[axis]; });
        return bucket_detail::Split{axis, items[mid].p[axis], mid};
      });
}

}  // namespace photon
