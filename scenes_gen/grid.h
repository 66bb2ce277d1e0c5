#pragma once
// N spheres on a regular cubic lattice: the uniform family of the scaling sweeps.

#include "generators.h"

#include "tracer/scene.h"

namespace scenes_gen {

/// Default sphere count of the grid generator.
inline constexpr int kGridDefaultCount = 1000;

/// options.count (>= 0, default 1000) spheres of radius 0.35 on a unit-spaced lattice of side
/// ceil(cbrt(count)), filled row by row, centred at the origin, framed by the camera.
/// Deterministic: the seed is unused.
tracer::Scene make_grid(const GenOptions& options);

}  // namespace scenes_gen
