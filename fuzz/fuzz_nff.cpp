// Fuzz target: the NFF parser (tracer::parse_nff, as render and convert read .nff files).
// Properties: a refusal is a SceneError "fuzz.nff:LINE: ..." of one short line; a scene that
// parses converts to JSON that the JSON loader accepts (convert never writes what render refuses).

#include "fuzz_check.h"

#include "tracer/nff.h"
#include "tracer/scene_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tracer::Scene scene;
  try {
    scene = tracer::parse_nff(fuzz::text_of(data, size), "fuzz.nff");
  } catch (const tracer::SceneError& e) {
    fuzz::check_message(e.what(), "fuzz.nff:");
    return 0;
  }
  const std::string text = tracer::scene_to_json(scene).dump(1);
  try {
    tracer::parse_scene_json(text);
  } catch (const tracer::SceneError& e) {
    fuzz::require(false, "an NFF scene converts to JSON that does not load", e.what());
  }
  return 0;
}
