#include "embree_points.h"

#include "knobs/config_error.h"

#include <chrono>
#include <stdexcept>
#include <string>

namespace accel {

void EmbreePoints::attach_spheres(std::span<const SphereShape> spheres) {
  BuildStats& stats = embree_.mutable_stats();
  if (spheres.size() != stats.primitives)
    throw std::invalid_argument(std::string(kName) + ": " + std::to_string(spheres.size()) +
                                " spheres attached to a structure over " + std::to_string(stats.primitives) +
                                " primitives");
  const auto start = std::chrono::steady_clock::now();
  embree_detail::Scene scene = embree_.new_scene();
  if (!spheres.empty()) {
    RTCGeometry geom = rtcNewGeometry(embree_.device(), RTC_GEOMETRY_TYPE_SPHERE_POINT);
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
  embree_.commit(scene);  // throws on the budget (a refused buffer included) and Embree's errors
  embree_.replace_scene(std::move(scene));
  native_ = true;
  stats.build_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace accel
