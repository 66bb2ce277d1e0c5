#pragma once
// The ray sets the tracing benchmarks trace (bench_trace, trace_counts): camera rays, rays
// spawned off their hits, and shadow rays to the lights.

#include "accel/geometry.h"
#include "tracer/intersector.h"
#include "tracer/scene.h"

#include <vector>

namespace bench {

/// One camera ray per pixel of a width x height image, row by row.
std::vector<accel::Ray> camera_rays(const tracer::Scene& scene, int width, int height);

/// Secondary rays off the camera hits (of bounded primitives, not the floor): mirror reflections
/// at even hits, uniformly random directions over the hemisphere at odd ones (diffuse and
/// shadow-like). Seeded.
std::vector<accel::Ray> spawned_rays(const tracer::Geometry& g, const std::vector<accel::Ray>& primary,
                                     const std::vector<tracer::Hit>& hits);

/// Shadow rays as the Whitted integrator casts them: from every bounded camera hit to every
/// light on its side, leaving on the lit side and ending just short of the light.
std::vector<accel::Ray> shadow_rays(const tracer::Scene& scene, const std::vector<accel::Ray>& primary,
                                    const std::vector<tracer::Hit>& hits);

}  // namespace bench
