#pragma once
// Camera and light placement that frame a generated block of geometry, whatever its size.

#include "tracer/scene.h"

#include "accel/geometry.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace scenes_gen {

/// A camera looking at the centre of `bounds` from direction `view_dir` (from the centre
/// towards the eye), far enough that the bounding sphere fills the vertical field of view.
inline tracer::Camera frame_bounds(const accel::Aabb& bounds, tracer::Vec3 view_dir,
                                   tracer::Vec3 up = {0.0f, 1.0f, 0.0f}, float vfov_deg = 40.0f) {
  const tracer::Vec3 centre = 0.5f * (bounds.lo + bounds.hi);
  const float radius = std::max(0.5f * glm::length(bounds.hi - bounds.lo), 1e-3f);
  const float half_fov = 0.5f * vfov_deg * 3.14159265f / 180.0f;
  tracer::Camera camera;
  camera.look_at = centre;
  camera.position = centre + glm::normalize(view_dir) * (1.05f * radius / std::sin(half_fov));
  camera.up = up;
  camera.vfov_deg = vfov_deg;
  return camera;
}

/// A point light at `centre + offset * scale` whose power keeps the irradiance at the centre
/// the same for any scale (inverse-square falloff).
inline tracer::PointLight light_at(const tracer::Vec3& centre, const tracer::Vec3& offset, float scale,
                                   float power_at_unit_scale_w) {
  tracer::PointLight light;
  light.position = centre + offset * scale;
  light.power_w = power_at_unit_scale_w * scale * scale;
  return light;
}

}  // namespace scenes_gen
