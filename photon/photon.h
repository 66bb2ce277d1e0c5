#pragma once
// The photon record: Jensen's 20 bytes (position, shared-exponent power, spherical-angle
// direction, split-axis flag). The balanced photon tree stores the records themselves as its
// nodes, so the size is what a gather touches per photon.

#include "packed_direction.h"
#include "packed_power.h"

#include <glm/vec3.hpp>

#include <cstdint>

namespace photon {

struct Photon {
  Vec3 position{0.0f};       ///< Where the photon was stored, world units.
  PackedPower power_bits{};  ///< Power, watts per channel (packed_power.h: within 0.39 %).
  PackedDirection dir_bits;  ///< Direction of travel when it arrived (packed_direction.h).
  std::uint16_t flags = 0;   ///< Low 2 bits: split axis of the node this record is in a
                             ///< balanced tree (0, 1, 2), or 3 when it is a leaf.

  /// A record for a photon of power `power` (watts per channel) arriving at `position` along
  /// `direction` (direction of travel, towards the surface; need not be unit length).
  static Photon make(const Vec3& position, const Color& power, const Vec3& direction) {
    Photon p;
    p.position = position;
    p.power_bits = pack_power(power);
    p.dir_bits = pack_direction(direction);
    return p;
  }

  /// Decoded power, watts per channel.
  Color power() const { return unpack_power(power_bits); }
  /// Decoded unit direction of travel.
  Vec3 direction() const { return unpack_direction(dir_bits); }
  /// True when the photon arrived from the side `normal` points to (dot(direction, normal) < 0):
  /// the hemisphere test of the paper's optimisation 2.
  bool arrives_from_side_of(const Vec3& normal) const {
    const Vec3 d = direction();
    return d.x * normal.x + d.y * normal.y + d.z * normal.z < 0.0f;
  }
};

static_assert(sizeof(Photon) == 20, "Jensen's photon record is 20 bytes");

}  // namespace photon
