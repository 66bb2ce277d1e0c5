#include "harness/sweep_resume.h"

#include "harness/sweep_results.h"

#include "input/message.h"

namespace harness {

using nlohmann::json;

ResumeState check_resume(const JsonlContents& contents, const std::string& name, const SweepDefinition& definition,
                         const json& shard_json, const std::vector<SweepConfig>& mine) {
  ResumeState state;
  state.valid_bytes = contents.valid_bytes;
  state.torn_tail = contents.torn_tail;
  if (contents.records.empty()) {
    // Nothing complete, but bytes that are not ours: do not overwrite them without a word.
    if (contents.valid_bytes > 0 || contents.torn_tail)
      throw SweepError(name + ":1: not a sweep JSON Lines file (no complete header line); cannot --resume it");
    return state;
  }
  const auto at = [&](std::size_t i) { return name + ":" + std::to_string(contents.lines[i]) + ": "; };
  const json& header = contents.records.front();
  if (header.value("kind", json()) != kHeaderKind || !header.contains("machine") || !header["machine"].is_object())
    throw SweepError(at(0) + "not a sweep header; cannot --resume from this file");
  if (header.value("sweep", json()) != to_json(definition))
    throw SweepError(at(0) + "written by a different sweep definition; cannot --resume it (pick another --jsonl)");
  if (header.value("shard", json()) != shard_json)
    throw SweepError(at(0) + "written for shard " + input::brief(header.value("shard", json())) + ", not " +
                     input::brief(shard_json) + "; cannot --resume it");
  state.machine = header["machine"];

  const auto by_key = configs_by_key(mine);
  std::map<std::string, std::size_t> line_of;
  for (std::size_t i = 1; i < contents.records.size(); ++i) {
    const json& r = contents.records[i];
    const json kind = r.value("kind", json());
    if (kind == kRowKind) {
      std::string key;
      try {
        key = check_row(r, by_key, definition, at(i)).key;
      } catch (const SweepError& e) {
        throw SweepError(std::string(e.what()) + " (in shard " + input::brief(shard_json) + "); cannot --resume");
      }
      if (const auto [it, fresh] = line_of.emplace(key, contents.lines[i]); !fresh)
        throw SweepError(at(i) + "configuration " + input::brief(json(key), 80) + " is already on line " +
                         std::to_string(it->second) + "; cannot --resume");
      state.done.emplace(key, r);
    } else if (kind == kResumeKind) {
      if (!r.contains("machine") || !r["machine"].is_object())
        throw SweepError(at(i) + "/machine: a resume record needs the machine that resumed; cannot --resume");
    } else if (kind != kRunKind) {
      throw SweepError(at(i) + "/kind: must be \"row\", \"resume\" or \"run\" after the header, got " +
                       input::brief(kind) + "; cannot --resume");
    }
  }
  state.records = contents.records;
  return state;
}

}  // namespace harness
