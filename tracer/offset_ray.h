#pragma once
// Origins of secondary rays that never re-hit the surface they leave.
//
// A fixed epsilon fails in both directions: 1e-4 is below one ulp at coordinates near 1e5
// (0.0078), and far too large near the origin. Following Wächter and Binder (Ray Tracing Gems,
// ch. 6), each coordinate moves along the normal by a fixed number of ulps of itself, so the
// offset scales with |p|; near zero, where ulps vanish, a small constant offset takes over.
// The hit point should be computed from the surface (re-projected), so that its own error is a
// few ulps of the surface's coordinates.

#include "accel/geometry.h"

#include <bit>
#include <cmath>
#include <cstdint>

namespace tracer {

namespace offset_ray_detail {
/// Below this |coordinate| the offset is the constant kFloatScale.
inline constexpr float kOriginRegion = 1.0f / 32.0f;
/// Constant offset near the origin, world units per unit of normal component.
inline constexpr float kFloatScale = 1.0f / 65536.0f;
/// Ulps moved per unit of normal component away from the origin.
inline constexpr float kIntScale = 256.0f;
}  // namespace offset_ray_detail

/// The point p moved off its surface to the side the unit normal `n` points to. Start a ray there
/// with tmin = 0 to leave the surface on that side (n for reflection, -n for transmission).
inline accel::Vec3 offset_ray_origin(const accel::Vec3& p, const accel::Vec3& n) {
  using namespace offset_ray_detail;
  accel::Vec3 out;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(p[a]) < kOriginRegion) {
      out[a] = p[a] + kFloatScale * n[a];
      continue;
    }
    // Moving the bit pattern by k ulps moves away from zero for positive k; so the step's sign
    // follows n for positive coordinates and flips for negative ones. Unsigned arithmetic keeps
    // the wrap-around defined (it cannot happen for finite |p| >= 1/32 anyway).
    const std::int32_t ulps = static_cast<std::int32_t>(kIntScale * n[a]);
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(p[a]);
    const std::int32_t step = p[a] < 0.0f ? -ulps : ulps;
    out[a] = std::bit_cast<float>(bits + static_cast<std::uint32_t>(step));
  }
  return out;
}

}  // namespace tracer
