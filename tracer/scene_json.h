#pragma once
// Scenes as JSON: every key validated, unknown keys rejected, errors as one line that starts
// with the JSON pointer of the offending value, e.g. `/spheres/12/radius: must be > 0, got -1`.
// The format is documented key by key in docs/scene-format.md.

#include "scene.h"
#include "scene_error.h"

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>

namespace tracer {

/// Where a scene's model files are found, and how much memory loading them may take.
struct SceneReadContext {
  std::string base_dir;                ///< Folder that mesh "file" paths are relative to; "" = the working folder.
  std::uint64_t max_memory_bytes = 0;  ///< --max-memory budget for loading a mesh; 0 = 25% of RAM.
};

/// Builds and validates a scene from parsed JSON; throws SceneError. Meshes are expanded into
/// triangles (model files read through load_mesh_file), and geometry.finalize() has been called
/// on the result.
Scene scene_from_json(const nlohmann::json& doc, const SceneReadContext& context = {});

/// Parses JSON text (input::parse_json: nesting limit, duplicate keys refused) and builds the
/// scene; syntax errors also name the JSON pointer and the line where they occur (and a NaN or
/// Infinity literal is reported as a non-finite number there).
Scene parse_scene_json(std::string_view text, const SceneReadContext& context = {});

/// Every key of the scene, defaults included, as scene_from_json reads it back: load, save and
/// load again gives an identical scene (floats are written in their shortest exact form).
nlohmann::json scene_to_json(const Scene& scene);

}  // namespace tracer
