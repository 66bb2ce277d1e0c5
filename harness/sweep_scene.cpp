#include "harness/sweep_scene.h"

#include "scenes_gen/generators.h"
#include "tracer/scene_io.h"

namespace harness {

tracer::Scene load_sweep_scene(const SceneSpec& spec) {
  if (spec.source == SceneSource::File) return tracer::load_scene_file(spec.file);
  scenes_gen::GenOptions options;
  options.seed = spec.seed;
  options.count = spec.count;
  options.model = spec.model;
  return scenes_gen::generate(spec.generator, options);
}

}  // namespace harness
