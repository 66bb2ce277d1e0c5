#pragma once
// The Whitted integrator's accuracy knobs: recursion depth, path-weight cut-off, samples per
// pixel, the seed of the sample jitter, and the precision of the geometry. Each defaults to the scene's own setting, so a render
// without knobs is the scene as written; a knob given overrides the scene for that render. These
// are the knobs `accelbench fronts` trades against time (docs/accuracy.md).

#include "scalar.h"
#include "scene.h"

#include "knobs/knob_table.h"

#include <cstdint>

namespace tracer {

struct WhittedParams {
  /// Maximum recursion depth (camera ray = 1); 0 = the scene's render.max_depth.
  int max_depth = 0;
  /// Paths whose weight falls below this are cut; -1 = the scene's min_weight.
  double min_weight = -1.0;
  /// Camera rays per pixel; 0 = the scene camera's samples_per_pixel.
  int spp = 0;
  /// Seed of the stratified sub-pixel jitter; 0 = the fixed pattern every earlier render used.
  /// Renders with other seeds are independent estimates of the same image (spp > 1).
  std::uint64_t seed = 0;
  /// Arithmetic of the geometry: "float" traces through the given structure; "double" traces
  /// the naive loop over every primitive in double (the float renderer's reference,
  /// tracer/naive_reference.h; the structure is not used).
  Precision precision = Precision::Float;
  /// Ray/triangle routine: watertight, or Moller-Trumbore (faster, can leak through edges).
  TriangleTest triangle = TriangleTest::Watertight;

  /// The recursion limits of `scene` with the knobs given here applied.
  RenderSettings limits(const Scene& scene) const;
  /// Samples per pixel on `scene`: the knob, or the camera's.
  int samples_per_pixel(const Scene& scene) const;

  /// The table: JSON, --param, sweeps and the fronts of max_depth, min_weight, spp and precision.
  static const knobs::KnobTable<WhittedParams>& knobs();
};

}  // namespace tracer
