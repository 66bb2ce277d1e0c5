#pragma once
// The photon-mapping scenes (the paper's Figures 4 and 5, a Cornell box, and the analytic
// furnace), each choosing the photon integrator with knobs sized for it.

#include "generators.h"

namespace scenes_gen {

/// The furnace: a point light of power `power_w` at the centre of a closed diffuse sphere of
/// radius `radius` and grey albedo `albedo`, seen from inside. Every wall point has the radiance
/// albedo * power / (4 pi^2 radius^2 (1 - albedo)) when all bounces are counted, and
/// albedo * power / (4 pi^2 radius^2) from direct light alone.
tracer::Scene make_furnace_scene(float radius, float albedo, float power_w);

}  // namespace scenes_gen
