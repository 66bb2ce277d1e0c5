#include "leaf_boxes.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace accel {

void LeafBoxes::build(std::span<const std::uint32_t> ids, std::span<const Aabb> boxes) {
  const std::size_t n = ids.size() + kLanes;  // a leaf's last load may run past its end
  for (auto& p : planes_) p.assign(n, 0.0f);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ids.size(), 1u << 14), [&](const auto& r) {
    for (std::size_t j = r.begin(); j < r.end(); ++j) {
      const Aabb& b = boxes[ids[j]];
      for (int a = 0; a < 3; ++a) {
        const float pad = box_pad(b.lo[a], b.hi[a]);
        planes_[2 * a][j] = b.lo[a] - pad;
        planes_[2 * a + 1][j] = b.hi[a] + pad;
      }
    }
  });
}

}  // namespace accel
