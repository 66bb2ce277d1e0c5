#include "harness/sweep_results.h"

#include "harness/sweep_machine.h"

#include "input/file_read.h"
#include "input/json_read.h"
#include "input/message.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

namespace harness {
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
    out << doc.dump(1, ' ', false, json::error_handler_t::replace) << "\n";
    if (!out.flush()) throw SweepError(path + ": write failed");
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw SweepError(path + ": cannot rename " + tmp + ": " + ec.message());
}

std::map<std::string, const SweepConfig*> configs_by_key(const std::vector<SweepConfig>& configs) {
  std::map<std::string, const SweepConfig*> out;
  for (const auto& c : configs) out.emplace(c.key, &c);
  return out;
}

const SweepConfig& check_row(const json& row, const std::map<std::string, const SweepConfig*>& configs,
                             const SweepDefinition& definition, const std::string& where) {
  const auto fail = [&](const std::string& field, const std::string& message) -> void {
    throw SweepError(where + "/" + field + ": " + message);
  };
  if (!row.is_object()) throw SweepError(where + ": a row must be an object, got " + input::brief(row));
  if (!row.contains("key")) fail("key", "missing");
  if (!row["key"].is_string()) fail("key", "must be a string, got " + input::brief(row["key"]));
  const auto it = configs.find(row["key"].get<std::string>());
  if (it == configs.end())
    fail("key", input::brief(row["key"], 80) + " is not a configuration of this sweep");
  const SweepConfig& c = *it->second;
  if (!row.contains("index") || !row["index"].is_number_unsigned() || row["index"].get<std::uint64_t>() != c.index)
    fail("index", "must be " + std::to_string(c.index) + " (the index of " + input::brief(row["key"], 80) + "), got " +
                      (row.contains("index") ? input::brief(row["index"]) : std::string("nothing")));
  if (row.value("scene", json()) != definition.scenes[c.scene].name)
    fail("scene", "must be \"" + definition.scenes[c.scene].name + "\" to match the key");
  if (row.value("structure", json()) != c.structure) fail("structure", "must be \"" + c.structure + "\" to match the key");
  if (row.value("requested", json()) != c.params) fail("requested", "must be " + input::brief(c.params, 80) + " to match the key");
  if (row.value("integrator_params", json::object()) != c.integrator_params)
    fail("integrator_params", "must be " + input::brief(c.integrator_params, 80) + " to match the key");
  const json status = row.value("status", json());
  if (status != "ok" && status != "failed" && status != "error")
    fail("status", "must be \"ok\", \"failed\" or \"error\", got " + input::brief(status));
  if (status == "ok") {
    const json& t = row.contains("render_ms") ? row["render_ms"] : json();
    if (!t.is_object() || !t.contains("median") || !t["median"].is_number() || !(t["median"].get<double>() >= 0.0))
      fail("render_ms", "an ok row needs render_ms with a median >= 0, got " + input::brief(t));
  }
  return c;
}

json parse_results_text(std::string_view text, const std::string& name) {
  json doc;
  try {
    doc = input::parse_json(text);
  } catch (const input::InputError& e) {
    throw SweepError(name + ": " + e.what());
  }
  if (!doc.is_object() || doc.value("format", json()) != kResultsFormat)
    throw SweepError(name + ": /format: not an accelbench results file");
  if (doc.value("version", json()) != kResultsVersion)
    throw SweepError(name + ": /version: expected " + std::to_string(kResultsVersion) + ", got " +
                     input::brief(doc.value("version", json())));
  for (const char* key : {"sweep", "rows", "machine", "shard"})
    if (!doc.contains(key)) throw SweepError(name + ": /" + key + ": missing");
  if (!doc["rows"].is_array()) throw SweepError(name + ": /rows: must be an array, got " + input::brief(doc["rows"]));
  if (!doc["machine"].is_object())
    throw SweepError(name + ": /machine: must be an object, got " + input::brief(doc["machine"]));
  if (doc.contains("runs") && !doc["runs"].is_array())
    throw SweepError(name + ": /runs: must be an array, got " + input::brief(doc["runs"]));
  const json& shard = doc["shard"];
  const auto count_of = [&](const char* key) -> std::int64_t {
    if (!shard.is_object() || !shard.contains(key) || !shard[key].is_number_integer())
      throw SweepError(name + ": /shard/" + key + ": must be an integer, got " +
                       (shard.is_object() && shard.contains(key) ? input::brief(shard[key]) : input::brief(shard)));
    return shard[key].get<std::int64_t>();
  };
  const std::int64_t index = count_of("index"), count = count_of("count");
  if (count < 1 || count > 1'000'000)
    throw SweepError(name + ": /shard/count: must be in [1, 1000000], got " + std::to_string(count));
  if (index < 0 || index >= count)
    throw SweepError(name + ": /shard/index: must be in [0, " + std::to_string(count - 1) + "] (count is " +
                     std::to_string(count) + "), got " + std::to_string(index));
  // Every row must be a configuration of the file's own sweep, in its shard.
  SweepDefinition definition;
  try {
    definition = parse_sweep_definition(doc["sweep"]);
  } catch (const SweepError& e) {
    throw SweepError(name + ": /sweep" + e.what());
  }
  const std::vector<SweepConfig> all = expand(definition);
  const auto by_key = configs_by_key(all);
  std::set<std::string> seen;
  for (std::size_t i = 0; i < doc["rows"].size(); ++i) {
    const std::string where = name + ": /rows/" + std::to_string(i);
    const SweepConfig& c = check_row(doc["rows"][i], by_key, definition, where);
    if (std::int64_t(c.index % std::uint64_t(count)) != index)
      throw SweepError(where + "/index: " + std::to_string(c.index) + " is not in shard " + std::to_string(index) +
                       "/" + std::to_string(count));
    if (!seen.insert(c.key).second)
      throw SweepError(where + ": configuration " + input::brief(json(c.key), 80) + " appears twice in this file");
  }
  return doc;
}

json read_results_file(const std::string& path) {
  return parse_results_text(read_input_file(path, input::kMaxResultsFileBytes, "results file"), path);
}

json merge_results(const std::vector<std::pair<std::string, json>>& inputs) {
  if (inputs.empty()) throw SweepError("merge: no input files");
  const json& first = inputs.front().second;
  SweepDefinition definition;
  try {
    definition = parse_sweep_definition(first.at("sweep"));
  } catch (const SweepError& e) {
    throw SweepError(inputs.front().first + ": /sweep" + e.what());
  }
  const std::vector<SweepConfig> all = expand(definition);
  const auto by_key = configs_by_key(all);
  std::map<std::string, std::string> owner;  // key -> file
  std::map<std::size_t, json> rows;
  json runs = json::array(), merged_from = json::array(), machines = json::array();
  for (const auto& [path, doc] : inputs) {
    if (doc["sweep"] != first["sweep"])
      throw SweepError(path + ": /sweep: differs from " + inputs.front().first + "'s sweep definition");
    for (std::size_t i = 0; i < doc["rows"].size(); ++i) {
      const json& row = doc["rows"][i];
      const SweepConfig& c = check_row(row, by_key, definition, path + ": /rows/" + std::to_string(i));
      const auto [it, fresh] = owner.emplace(c.key, path);
      if (!fresh)
        throw SweepError(path + ": /rows/" + std::to_string(i) + ": configuration " + input::brief(json(c.key), 80) +
                         " is also in " + it->second);
      rows.emplace(c.index, row);
    }
    for (const auto& r : doc.value("runs", json::array())) runs.push_back(r);
    merged_from.push_back({{"file", path}, {"shard", doc.value("shard", json())}, {"machine", doc["machine"]}});
    machines.push_back(doc["machine"]);
    if (doc.contains("machines") && doc["machines"].is_array())
      for (const auto& m : doc["machines"]) machines.push_back(m);
  }
  json missing = json::array();
  for (const auto& c : all)
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

}  // namespace harness
