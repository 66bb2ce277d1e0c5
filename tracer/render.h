#pragma once
// Renders a scene through one acceleration structure: tiles on all cores, bit-identical at any
// thread count.

#include "image.h"
#include "ray_counts.h"
#include "scene.h"

#include "accel/accel.h"

namespace tracer {

struct RenderOptions {
  int threads = 0;               ///< Worker threads; 0 = every hardware thread.
  bool count_traversal = false;  ///< Gather TraversalCounters (slower; never for timing).
  int width = 0;                 ///< Image width, pixels; 0 = the scene camera's.
  int height = 0;                ///< Image height, pixels; 0 = the scene camera's.
};

struct RenderResult {
  Image image;                         ///< Linear RGB radiance per pixel.
  RayCounts rays;                      ///< Rays traced, by kind.
  accel::TraversalCounters traversal;  ///< Summed over all rays; zero unless counted.
  double render_ms = 0;                ///< Wall-clock time of the tile loop, milliseconds.
};

/// Renders `scene` with the Whitted integrator through `accel`, which must have been built over
/// scene.geometry.primitive_bounds(). Throws std::invalid_argument on bad options.
RenderResult render(const Scene& scene, const accel::AnyAccel& accel, const RenderOptions& options);

/// The number of worker threads `threads` resolves to (0 = hardware threads, at least 1).
int resolve_threads(int threads);

/// Sub-pixel offset in [0, 1)^2 of sample `s` of `spp` in pixel (x, y): stratified on a
/// ceil(sqrt(spp)) grid and jittered by a hash of (x, y, s), so it is the same on every run and
/// thread. A single sample sits at the pixel centre.
void sample_offset(int x, int y, int s, int spp, float& jx, float& jy);

}  // namespace tracer
