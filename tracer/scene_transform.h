#pragma once
// Moving and scaling a whole scene: camera, lights and every primitive together, so that the
// image should not change. The stability suite renders scenes this way at the extremes.

#include "scene.h"

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

}  // namespace tracer
