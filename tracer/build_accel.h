#pragma once
// Building a structure over a scene's geometry as every render does: over the primitives' bounds,
// with the triangles' own cell test for the trees that divide space, and the spheres attached for
// the SIMD leaves.

#include "intersector.h"
#include "scene_geometry.h"
#include "triangle_box.h"

#include "accel/accel.h"

#include <nlohmann/json.hpp>

#include <span>
#include <string_view>

namespace tracer {

/// accel::make_accel over `boxes` (geometry.primitive_bounds(), computed once by the caller) with
/// primitive_overlap(geometry) in the limits, then attach_geometry (which the limits announce:
/// BuildLimits::shapes_follow). Throws knobs::ConfigError.
inline accel::AnyAccel build_accel(std::string_view name, const nlohmann::json& params, const Geometry& geometry,
                                   std::span<const accel::Aabb> boxes, accel::BuildLimits limits = {}) {
  limits.overlap = primitive_overlap(geometry);
  limits.shapes_follow = sphere_only(geometry) || triangle_only(geometry);
  accel::AnyAccel a = accel::make_accel(name, params, boxes, limits);
  attach_geometry(a, geometry);
  return a;
}

}  // namespace tracer
