#include "embree_triangles.h"

#include <chrono>
#include <cstring>
#include <unordered_map>
#include <vector>

namespace accel {

namespace {

/// A vertex position by its bits, so that only exactly equal positions are shared.
struct VertexKey {
  std::uint32_t x, y, z;
  bool operator==(const VertexKey&) const = default;
};
struct VertexKeyHash {
  std::size_t operator()(const VertexKey& k) const {
    std::uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
    h = (h ^ k.y) * 0xC2B2AE3D27D4EB4Full;
    h = (h ^ k.z) * 0x165667B19E3779F9ull;
    return std::size_t(h ^ (h >> 29));
  }
};
VertexKey key_of(const Vec3& p) {
  VertexKey k;
  std::memcpy(&k.x, &p.x, 4);
  std::memcpy(&k.y, &p.y, 4);
  std::memcpy(&k.z, &p.z, 4);
  return k;
}

/// The triangles as an indexed mesh: one vertex per distinct position, three indices each.
struct IndexedMesh {
  std::vector<Vec3> vertices;
  std::vector<std::uint32_t> indices;
};
IndexedMesh share_vertices(std::span<const TriangleShape> triangles) {
  IndexedMesh mesh;
  mesh.indices.reserve(3 * triangles.size());
  std::unordered_map<VertexKey, std::uint32_t, VertexKeyHash> index_of;
  index_of.reserve(triangles.size());
  for (const TriangleShape& t : triangles)
    for (const Vec3& p : {t.p0, t.p1, t.p2}) {
      const auto [it, added] = index_of.try_emplace(key_of(p), std::uint32_t(mesh.vertices.size()));
      if (added) mesh.vertices.push_back(p);
      mesh.indices.push_back(it->second);
    }
  return mesh;
}

}  // namespace

void EmbreeTriangles::attach_triangles(std::span<const TriangleShape> triangles) {
  check_count(triangles.size(), kName, "triangles");
  const IndexedMesh mesh = share_vertices(triangles);
  embree_detail::Scene scene = new_scene();
  if (!triangles.empty()) {
    RTCGeometry geom = rtcNewGeometry(device(), RTC_GEOMETRY_TYPE_TRIANGLE);
    // rtcSetNewGeometryBuffer pads the vertex buffer for Embree's 16-byte loads itself.
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), mesh.vertices.size()));
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                3 * sizeof(unsigned), triangles.size()));
    if (v && idx) {
      std::memcpy(v, mesh.vertices.data(), mesh.vertices.size() * sizeof(Vec3));
      std::memcpy(idx, mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t));
      rtcCommitGeometry(geom);
      rtcAttachGeometry(scene.get(), geom);
    }
    rtcReleaseGeometry(geom);
  }
  make_native(std::move(scene), std::chrono::steady_clock::now());
}

}  // namespace accel
