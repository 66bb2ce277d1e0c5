#include "triangle_soa.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace accel {

void TriangleSoA::build(std::span<const std::uint32_t> ids, std::span<const LeafRange> leaves,
                        std::span<const TriangleShape> triangles) {
  *this = {};
  if (triangles.empty()) return;
  // Padded by one batch: the last leaf's loads may run past its end (those lanes are ignored).
  data_.assign(9 * ids.size() + kLanes, 0.0f);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size(), 1u << 12), [&](const auto& r) {
    for (std::size_t l = r.begin(); l < r.end(); ++l) {
      const auto [first, count] = leaves[l];
      float* leaf = data_.data() + 9 * std::size_t(first);
      for (std::uint32_t i = 0; i < count; ++i) {
        const TriangleShape& t = triangles[ids[first + i]];
        const Vec3* p[3] = {&t.p0, &t.p1, &t.p2};
        for (int v = 0; v < 3; ++v)
          for (int a = 0; a < 3; ++a) leaf[std::size_t(3 * v + a) * count + i] = (*p[v])[a];
      }
    }
  });
}

}  // namespace accel
