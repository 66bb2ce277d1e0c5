#include "triangle_soa.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace accel {

void TriangleSoA::build(std::span<const std::uint32_t> ids, std::span<const TriangleShape> triangles) {
  *this = {};
  if (triangles.empty()) return;
  // Padded by one batch: a leaf's last load may run past its end (those lanes are ignored).
  const std::size_t n = ids.size() + kLanes;
  for (auto& c : coords_) c.assign(n, 0.0f);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ids.size(), 1u << 14), [&](const auto& r) {
    for (std::size_t j = r.begin(); j < r.end(); ++j) {
      const TriangleShape& t = triangles[ids[j]];
      const Vec3* p[3] = {&t.p0, &t.p1, &t.p2};
      for (int v = 0; v < 3; ++v)
        for (int a = 0; a < 3; ++a) coords_[3 * v + a][j] = (*p[v])[a];
    }
  });
}

}  // namespace accel
