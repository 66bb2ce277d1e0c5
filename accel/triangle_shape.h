#pragma once
// A triangle as the structures see it: its three vertices, nothing about shading; and which
// ray/triangle routine a leaf function runs on it.

#include "geometry.h"

#include <cstdint>

namespace accel {

struct TriangleShape {
  Vec3 p0{0.0f}, p1{0.0f}, p2{0.0f};  ///< Vertices, world units, counter-clockwise.
};

/// The ray/triangle routine of a render (the tracer's `triangle` knob, tracer/triangle_test.h).
enum class TriangleTest : std::uint8_t {
  Watertight,  ///< Woop-Benthin-Wald: edge functions in a ray-aligned shear frame; never leaks.
  Moller,      ///< Moller-Trumbore: faster; can leak through shared edges and vertices.
};

}  // namespace accel
