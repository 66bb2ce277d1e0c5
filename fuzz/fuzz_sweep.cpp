// Fuzz target: the sweep-file reader (harness::parse_sweep_text, as sweep --config reads it).
// Properties: a refusal is a SweepError "fuzz.json: ..." of one short line; an accepted
// definition expands within the configuration limit, and its normal form reads back to itself
// (the form written into every results file and JSON Lines header).

#include "fuzz_check.h"

#include "harness/sweep_definition.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  harness::SweepDefinition d;
  try {
    d = harness::parse_sweep_text(fuzz::text_of(data, size), "fuzz.json");
  } catch (const harness::SweepError& e) {
    fuzz::check_message(e.what(), "fuzz.json: ");
    return 0;
  }
  const std::vector<harness::SweepConfig> configs = harness::expand(d);
  fuzz::require(configs.size() <= harness::kMaxConfigurations, "a sweep expands past the limit");
  const nlohmann::json normal = harness::to_json(d);
  try {
    fuzz::require(harness::to_json(harness::parse_sweep_definition(normal)) == normal,
                  "the normal form does not read back to itself", normal.dump());
  } catch (const harness::SweepError& e) {
    fuzz::require(false, "the normal form of an accepted sweep is refused", e.what());
  }
  return 0;
}
