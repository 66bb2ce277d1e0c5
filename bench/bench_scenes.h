#pragma once
// The scenes the tracing benchmarks name (bench_trace, trace_counts): the generators' scenes,
// random1M, the shared meshes and the triangle scaling figure's scenes.

#include "scenes_gen/generators.h"
#include "tracer/scene.h"

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace bench {

/// The triangle-mesh scenes: three of the shared standard models, framed on a floor, and a
/// million triangles of instanced bunnies (mesh_grid). Present only with ../shared/meshes.
extern const std::vector<std::string> kMeshScenes;

/// Ten million triangles of instanced bunnies, for build times only (naive could not check rays).
extern const std::string kBuildOnlyMeshScene;

/// The scaling figure's scenes: copies of spot (the smallest shared model, 5,856 triangles) in a
/// grid, from one copy to 10^7 triangles, and spheres8000 with each sphere an icosphere of 0 to 3
/// subdivisions (160,000 to 10,240,000 triangles).
extern const std::vector<std::pair<std::string, std::uint64_t>> kSpotGrids;
extern const std::vector<std::pair<std::string, std::uint64_t>> kTessellated;

/// The generator and options of a scaling scene, or nothing for another name.
std::optional<std::pair<std::string, scenes_gen::GenOptions>> scaling_scene(const std::string& name);

/// True for the meshes, the build-only mesh and the scaling scenes (where naive would take hours).
bool is_mesh_scene(const std::string& name);

/// A benchmark scene by name: a generator's name, random1M (a million random spheres), one of
/// kMeshScenes, kBuildOnlyMeshScene or a scaling scene. Throws scenes_gen::GenError for an unknown
/// name, and the mesh loader's error where ../shared/meshes lacks a model.
tracer::Scene bench_scene(const std::string& name);

}  // namespace bench
