#pragma once
// Scene files by extension: the one entry point every command uses to read and write scenes.

#include "scene.h"
#include "scene_error.h"

#include <cstdint>
#include <string>

namespace tracer {

/// Loads a scene file, choosing the format by extension (.json, or .nff for Eric Haines' NFF).
/// Throws SceneError whose message starts with the path, e.g.
/// `scene.json: /spheres/3/radius: must be > 0, got -1` or `balls.nff:12: expected 4 numbers...`.
/// Mesh files a JSON scene names are read relative to its folder, within `max_memory_bytes`
/// (the --max-memory budget; 0 = 25% of RAM).
Scene load_scene_file(const std::string& path, std::uint64_t max_memory_bytes = 0);

/// Writes a scene as JSON (the only format written). Throws SceneError on I/O failure.
void save_scene_file(const Scene& scene, const std::string& path);

}  // namespace tracer
