// Fuzz target: the results-file reader behind merge (harness::parse_results_text,
// harness::merge_results). Properties: a refusal is a SweepError "fuzz.json: ..." of one short
// line; an accepted file merges on its own, and the merge is a results file that reads back.

#include "fuzz_check.h"

#include "harness/sweep_results.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  nlohmann::json doc;
  try {
    doc = harness::parse_results_text(fuzz::text_of(data, size), "fuzz.json");
  } catch (const harness::SweepError& e) {
    fuzz::check_message(e.what(), "fuzz.json: ");
    return 0;
  }
  nlohmann::json merged;
  try {
    merged = harness::merge_results({{"fuzz.json", doc}});
  } catch (const harness::SweepError& e) {
    fuzz::require(false, "an accepted results file does not merge on its own", e.what());
  }
  try {
    harness::parse_results_text(merged.dump(), "merged.json");
  } catch (const harness::SweepError& e) {
    fuzz::require(false, "a merge of accepted files is refused", e.what());
  }
  return 0;
}
