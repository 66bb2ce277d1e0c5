#pragma once
// Turns a sweep's scene entry into a scene: runs its generator or loads its file.

#include "harness/sweep_definition.h"

#include "tracer/scene.h"

namespace harness {

/// The scene a SceneSpec names. Throws std::exception with a one-line message on failure.
tracer::Scene load_sweep_scene(const SceneSpec& spec);

}  // namespace harness
