#include "embree_points.h"

#include <chrono>

namespace accel {

void EmbreePoints::attach_spheres(std::span<const SphereShape> spheres) {
  check_count(spheres.size(), kName, "spheres");
  const auto start = std::chrono::steady_clock::now();
  embree_detail::Scene scene = new_scene();
  if (!spheres.empty()) {
    RTCGeometry geom = rtcNewGeometry(device(), RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                          4 * sizeof(float), spheres.size()));
    if (v) {
      for (std::size_t i = 0; i < spheres.size(); ++i) {
        v[4 * i + 0] = spheres[i].center.x;
        v[4 * i + 1] = spheres[i].center.y;
        v[4 * i + 2] = spheres[i].center.z;
        v[4 * i + 3] = spheres[i].radius;
      }
      rtcCommitGeometry(geom);
      rtcAttachGeometry(scene.get(), geom);
    }
    rtcReleaseGeometry(geom);
  }
  make_native(std::move(scene), start);
}

}  // namespace accel
