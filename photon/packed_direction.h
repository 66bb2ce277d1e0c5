#pragma once
// A photon's direction of travel in 2 bytes: Jensen's spherical angles (theta from +z, phi
// around it), rounded to nearest and decoded through 256-entry tables.
//
// theta in [0, pi] is stored in 254 steps, phi in [0, 2 pi) in 256 steps (so the six axis
// directions decode exactly), and the decoded direction is within pi/508 in theta and
// pi/256 * sin(theta) across it of the true one: under 0.8 degrees. It is used only to cull photons arriving from behind a surface
// (the sign of a dot product), where that error matters only within 0.8 degrees of grazing.

#include "vec.h"

#include <array>
#include <cstdint>

namespace photon {

/// theta (0..254 over [0, pi]) and phi (0..255 over [0, 2 pi)).
struct PackedDirection {
  std::uint8_t theta = 0;  ///< Angle from +z, pi/254 radians per step (0..254).
  std::uint8_t phi = 0;    ///< Angle around +z from +x towards +y, 2 pi/256 radians per step.
};

/// Decoding tables: sin and cos of every stored theta and phi.
struct DirectionTables {
  std::array<float, 256> cos_theta, sin_theta, cos_phi, sin_phi;
};
/// The one set of tables, filled before main().
extern const DirectionTables kDirectionTables;

/// Encodes a direction; it need not be unit length, and the zero vector encodes as +z.
PackedDirection pack_direction(const Vec3& d);

/// The decoded unit direction.
inline Vec3 unpack_direction(PackedDirection p) {
  const DirectionTables& t = kDirectionTables;
  return {t.sin_theta[p.theta] * t.cos_phi[p.phi], t.sin_theta[p.theta] * t.sin_phi[p.phi],
          t.cos_theta[p.theta]};
}

}  // namespace photon
