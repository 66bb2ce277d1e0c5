#pragma once
// A triangle as the structures see it: its three vertices, nothing about shading.

#include "geometry.h"

namespace accel {

struct TriangleShape {
  Vec3 p0{0.0f}, p1{0.0f}, p2{0.0f};  ///< Vertices, world units, counter-clockwise.
};

}  // namespace accel
