// Fuzz target: the JSON Lines reader behind --resume (harness::parse_jsonl, harness::check_resume)
// for one fixed sweep definition and shard. Properties: a refusal is a SweepError of one short
// line naming the file; an accepted file never holds a row the shard cannot place, and the
// results assembled from it are a results file that merge accepts, complete exactly when every
// configuration has a row.

#include "fuzz_check.h"

#include "harness/sweep_jsonl.h"
#include "harness/sweep_results.h"
#include "harness/sweep_resume.h"

#include <set>

namespace {

/// The definition the corpus' files were written for (fuzz/corpus/sweep/fuzz.json): a sweep of 7
/// configurations, small enough that a mutated row often still places.
const harness::SweepDefinition& definition() {
  static const harness::SweepDefinition d = harness::parse_sweep_definition(nlohmann::json::parse(R"({
    "name": "fuzz", "scenes": ["five", "random:30"],
    "structures": ["naive", {"name": "kdtree", "max_depth": [4, 8]}],
    "resolution": "16x12", "repetitions": 1, "warmup": 0})"));
  return d;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const harness::SweepDefinition& d = definition();
  const std::vector<harness::SweepConfig> mine = harness::expand(d);
  const nlohmann::json shard = {{"index", 0}, {"count", 1}};
  harness::ResumeState state;
  try {
    state = harness::check_resume(harness::parse_jsonl(fuzz::text_of(data, size), "fuzz.jsonl"), "fuzz.jsonl", d, shard,
                                mine);
  } catch (const harness::SweepError& e) {
    fuzz::check_message(e.what(), "fuzz.jsonl:");
    return 0;
  }
  if (state.records.empty()) return 0;
  std::set<std::string> keys;
  for (const auto& c : mine) keys.insert(c.key);
  for (const auto& [key, row] : state.done) fuzz::require(keys.count(key) == 1, "a resumed row is not of the shard", key);
  const nlohmann::json results = harness::assemble_results(state.records, state.machine, d, 0, 1, mine);
  fuzz::require(results["complete"].get<bool>() == (state.done.size() == mine.size()),
                "complete does not match the rows");
  fuzz::require(results["rows"].size() + results["missing"].size() == mine.size(), "rows and missing do not add up");
  try {
    harness::parse_results_text(results.dump(), "assembled.json");
  } catch (const harness::SweepError& e) {
    fuzz::require(false, "results assembled from an accepted resume are refused", e.what());
  }
  return 0;
}
