#include "closed_meshes.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace scenes_gen {

namespace {

void finish(tracer::MeshData& m) {
  m.stats.vertices = m.vertices.size();
  m.stats.triangles = m.triangles.size();
}

}  // namespace

tracer::MeshData icosphere(int subdivisions) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<glm::dvec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                               {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (glm::dvec3& p : v) p = glm::normalize(p);
  std::vector<std::array<std::uint32_t, 3>> f = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoint;
    const auto mid = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto [it, added] = midpoint.try_emplace({key.first, key.second}, std::uint32_t(v.size()));
      if (added) v.push_back(glm::normalize(v[a] + v[b]));
      return it->second;
    };
    std::vector<std::array<std::uint32_t, 3>> next;
    next.reserve(4 * f.size());
    for (const auto& tri : f) {
      const std::uint32_t a = mid(tri[0], tri[1]), b = mid(tri[1], tri[2]), c = mid(tri[2], tri[0]);
      next.push_back({tri[0], a, c});
      next.push_back({tri[1], b, a});
      next.push_back({tri[2], c, b});
      next.push_back({a, b, c});
    }
    f = std::move(next);
  }
  tracer::MeshData m;
  m.vertices.reserve(v.size());
  for (const glm::dvec3& p : v) m.vertices.emplace_back(p);
  m.triangles = std::move(f);
  finish(m);
  return m;
}

tracer::MeshData grid_cube(int cells) {
  tracer::MeshData m;
  std::map<std::array<int, 3>, std::uint32_t> index;  // integer lattice point -> vertex
  const auto vertex = [&](std::array<int, 3> q) {
    const auto [it, added] = index.try_emplace(q, std::uint32_t(m.vertices.size()));
    if (added)
      m.vertices.emplace_back(float(-1.0 + 2.0 * q[0] / cells), float(-1.0 + 2.0 * q[1] / cells),
                              float(-1.0 + 2.0 * q[2] / cells));
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      for (int i = 0; i < cells; ++i)
        for (int j = 0; j < cells; ++j) {
          std::array<int, 3> q00{}, q10{}, q11{}, q01{};
          for (auto* q : {&q00, &q10, &q11, &q01}) (*q)[axis] = side * cells;
          q00[u] = i, q00[w] = j;
          q10[u] = i + 1, q10[w] = j;
          q11[u] = i + 1, q11[w] = j + 1;
          q01[u] = i, q01[w] = j + 1;
          const std::uint32_t a = vertex(q00), b = vertex(q10), c = vertex(q11), d = vertex(q01);
          // (u, w, axis) is right-handed: counter-clockwise in (u, w) faces +axis.
          if (side == 1) {
            m.triangles.push_back({a, b, c});
            m.triangles.push_back({a, c, d});
          } else {
            m.triangles.push_back({a, c, b});
            m.triangles.push_back({a, d, c});
          }
        }
    }
  finish(m);
  return m;
}

}  // namespace scenes_gen
