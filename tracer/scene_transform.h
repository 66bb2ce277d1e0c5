#pragma once
// Moving and scaling a whole scene: camera, lights and every primitive together, so that the
// image should not change. The stability suite renders scenes this way at the extremes.

#include "scene.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace tracer {

/// Moves every position of `scene` by `offset`, world units: the camera's eye and look-at
/// point, every light and every primitive (planes through their offset). Each coordinate is
/// rounded once to float, as a scene stored at that place would be.
void translate_scene(Scene& scene, const glm::dvec3& offset);

/// Scales every length of `scene` about the world origin by `factor` (> 0): positions, radii,
/// heights, plane offsets and the camera's hither distance. Light powers are multiplied by
/// factor^2 and absorption coefficients divided by factor, so that the irradiance at
/// corresponding points, and hence the image, stays the same.
void scale_scene(Scene& scene, double factor);

/// The centre of bounded primitive `id` (global id): a sphere's centre, the middle of a box or
/// of a cone's axis, the mean of a triangle's or polygon's vertices. World units.
glm::dvec3 primitive_centre(const Geometry& geometry, std::uint32_t id);

/// Moves bounded primitive `id` by `delta`, world units, each coordinate rounded once to float.
/// A sphere's centre lands exactly on centre + delta when that is a float.
void move_primitive(Geometry& geometry, std::uint32_t id, const glm::dvec3& delta);

/// Appends a copy of every bounded primitive, the copy of `id` moved by shifts[id] (world units;
/// shifts has one entry per bounded primitive), and, when `copy_planes`, a copy of every plane;
/// then finalize(). Copies keep their material and vertex normals; the originals keep their
/// ids, and each copy comes after the originals of its kind.
void append_copies(Geometry& geometry, const std::vector<glm::dvec3>& shifts, bool copy_planes);

}  // namespace tracer
