// Fuzz target: the JSON scene loader (tracer::parse_scene_json, as render, tune and sweep read
// scene files). Properties: a refusal is a SceneError of one short line; a scene that loads
// saves as JSON that loads back to the same scene (what `convert` and `gen` rely on).

#include "fuzz_check.h"

#include "tracer/scene_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tracer::Scene scene;
  try {
    scene = tracer::parse_scene_json(fuzz::text_of(data, size));
  } catch (const tracer::SceneError& e) {
    fuzz::check_message(e.what(), "");
    return 0;
  }
  const nlohmann::json saved = tracer::scene_to_json(scene);
  const std::string text = saved.dump(1);
  try {
    const tracer::Scene again = tracer::parse_scene_json(text);
    fuzz::require(tracer::scene_to_json(again) == saved, "a saved scene loads back different", text);
  } catch (const tracer::SceneError& e) {
    fuzz::require(false, "a loaded scene, saved, does not load back", e.what());
  }
  return 0;
}
