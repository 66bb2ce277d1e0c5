#pragma once
// Scenes around triangle meshes: a model file framed on a floor (`convert MODEL` and the `mesh`
// generator), and the standard models of ../shared/meshes by short name.

#include "tracer/scene.h"

#include <string>
#include <vector>

namespace scenes_gen {

/// The short names of the shared standard models (bunny, ogre, ...), in display order.
std::vector<std::string> model_names();

/// The file of a model: a short name from model_names() found in the meshes folder
/// ($ACCELBENCH_MESHES_DIR, else ../shared/meshes beside the source tree), or a path to a model
/// file as given. Throws GenError on an unknown name or a missing folder.
std::string model_path(const std::string& name_or_path);

/// A scene around the model at `path`, which keeps its own coordinates (identity transform; the
/// scene refers to the file): a grey diffuse model on a floor under its lowest point, a camera
/// framing it from the front right and above (y up), and two lights scaled to its size.
tracer::Scene scene_around_model(const std::string& path, std::uint64_t max_memory_bytes = 0);

}  // namespace scenes_gen
