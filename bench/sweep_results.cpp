#include "sweep_results.h"

#include "sweep_machine.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

namespace bench {
namespace {

using nlohmann::json;

json strip_kind(json record) {
  record.erase("kind");
  return record;
}

/// Records which machines measured the rows of `doc`, when more than one did.
void add_machines(json& doc, const json& machines) {
  const json distinct = distinct_machines(machines);
  if (distinct.size() > 1) doc["machines"] = distinct;
  if (json mixed = mixed_hardware(distinct); !mixed.is_null())
    doc["mixed_hardware"] = std::move(mixed);
}

}  // namespace

json assemble_results(const std::vector<json>& records, const json& machine, const SweepDefinition& definition,
                      int shard_index, int shard_count, const std::vector<SweepConfig>& expected) {
  std::map<std::size_t, json> rows;  // by index: ordered, first record of a key wins
  std::set<std::string> keys;
  json runs = json::array(), machines = json::array({machine});
  for (const auto& r : records) {
    const std::string kind = r.value("kind", "");
    if (kind == kResumeKind) {
      machines.push_back(r.value("machine", json()));
    } else if (kind == kRowKind) {
      const std::string key = r.value("key", "");
      if (keys.insert(key).second) rows.emplace(r.value("index", std::size_t(0)), strip_kind(r));
    } else if (kind == kRunKind) {
      runs.push_back(strip_kind(r));
    }
  }
  json missing = json::array();
  for (const auto& c : expected)
    if (!keys.count(c.key)) missing.push_back(c.key);
  json row_list = json::array();
  for (auto& [index, row] : rows) row_list.push_back(std::move(row));
  json doc = {{"format", kResultsFormat},
              {"version", kResultsVersion},
              {"machine", machine},
              {"sweep", to_json(definition)},
              {"shard", {{"index", shard_index}, {"count", shard_count}}},
              {"complete", missing.empty()},
              {"missing", missing},
              {"speedup_basis", kSpeedupBasis},
              {"runs", runs},
              {"rows", row_list}};
  add_machines(doc, machines);
  return doc;
}

void write_json_atomic(const std::string& path, const json& doc) {
  const std::filesystem::path p(path);
  std::error_code ec;
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path(), ec);
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    if (!out) throw SweepError(path + ": cannot write results");
    out << doc.dump(1) << "\n";
    if (!out.flush()) throw SweepError(path + ": write failed");
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw SweepError(path + ": cannot rename " + tmp + ": " + ec.message());
}

json read_results_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw SweepError(path + ": cannot open results file");
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::parse_error& e) {
    throw SweepError(path + ": not valid JSON (byte " + std::to_string(e.byte) + ")");
  }
  if (!doc.is_object() || doc.value("format", "") != kResultsFormat)
    throw SweepError(path + ": /format: not an accelbench results file");
  if (doc.value("version", 0) != kResultsVersion)
    throw SweepError(path + ": /version: expected " + std::to_string(kResultsVersion));
  for (const char* key : {"sweep", "rows", "machine"})
    if (!doc.contains(key)) throw SweepError(path + ": /" + key + ": missing");
  if (!doc["rows"].is_array()) throw SweepError(path + ": /rows: must be an array");
  return doc;
}

json merge_results(const std::vector<std::pair<std::string, json>>& inputs) {
  if (inputs.empty()) throw SweepError("merge: no input files");
  const json& first = inputs.front().second;
  SweepDefinition definition;
  try {
    definition = parse_sweep_definition(first["sweep"]);
  } catch (const SweepError& e) {
    throw SweepError(inputs.front().first + ": /sweep" + e.what());
  }
  std::map<std::string, std::string> owner;  // key -> file
  std::map<std::size_t, json> rows;
  json runs = json::array(), merged_from = json::array(), machines = json::array();
  for (const auto& [path, doc] : inputs) {
    if (doc["sweep"] != first["sweep"])
      throw SweepError(path + ": /sweep: differs from " + inputs.front().first + "'s sweep definition");
    for (std::size_t i = 0; i < doc["rows"].size(); ++i) {
      const json& row = doc["rows"][i];
      const std::string key = row.value("key", "");
      if (key.empty()) throw SweepError(path + ": /rows/" + std::to_string(i) + "/key: missing");
      const auto [it, fresh] = owner.emplace(key, path);
      if (!fresh) throw SweepError(path + ": /rows/" + std::to_string(i) + ": configuration " + key +
                                   " is also in " + it->second);
      rows.emplace(row.value("index", std::size_t(0)), row);
    }
    for (const auto& r : doc.value("runs", json::array())) runs.push_back(r);
    merged_from.push_back({{"file", path}, {"shard", doc.value("shard", json())}, {"machine", doc["machine"]}});
    machines.push_back(doc["machine"]);
    if (doc.contains("machines") && doc["machines"].is_array())
      for (const auto& m : doc["machines"]) machines.push_back(m);
  }
  json missing = json::array();
  for (const auto& c : expand(definition))
    if (!owner.count(c.key)) missing.push_back(c.key);
  json row_list = json::array();
  for (auto& [index, row] : rows) row_list.push_back(std::move(row));
  json doc = {{"format", kResultsFormat},
              {"version", kResultsVersion},
              {"machine", first["machine"]},
              {"sweep", first["sweep"]},
              {"shard", {{"index", 0}, {"count", 1}}},
              {"complete", missing.empty()},
              {"missing", missing},
              {"speedup_basis", kSpeedupBasis},
              {"runs", runs},
              {"merged_from", merged_from},
              {"rows", row_list}};
  add_machines(doc, machines);
  return doc;
}

}  // namespace bench
