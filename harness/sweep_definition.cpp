#include "harness/sweep_definition.h"

#include "integrators/integrators.h"

#include "accel/accel.h"
#include "input/file_read.h"
#include "input/json_read.h"
#include "input/message.h"
#include "scenes_gen/generators.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <set>
#include <sstream>

namespace harness {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& pointer, const std::string& message) {
  throw SweepError((pointer.empty() ? std::string("/") : input::display_pointer(pointer)) + ": " + message);
}

using input::brief;

std::string escape_key(const std::string& key) {
  // RFC 6901: '~' -> "~0", '/' -> "~1".
  std::string out;
  for (char c : key) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
  return out;
}

std::string child(const std::string& pointer, const std::string& key) {
  return pointer + "/" + escape_key(key);
}
std::string child(const std::string& pointer, std::size_t index) {
  return pointer + "/" + std::to_string(index);
}

void require_keys(const json& j, const std::string& pointer, std::initializer_list<const char*> allowed) {
  for (const auto& item : j.items()) {
    const std::string& key = item.key();  // a plain reference: clang 14 cannot capture a structured binding
    if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; }))
      fail(child(pointer, key), "unknown key");
  }
}

std::string get_string(const json& j, const std::string& pointer) {
  if (!j.is_string()) fail(pointer, "must be a string, got " + brief(j));
  return j.get<std::string>();
}

long long get_integer(const json& j, const std::string& pointer, long long lo, long long hi) {
  if (!j.is_number_integer() && !j.is_number_unsigned())
    fail(pointer, "must be an integer, got " + brief(j));
  const long long v = j.is_number_unsigned() && j.get<std::uint64_t>() > std::uint64_t(hi)
                          ? hi + 1
                          : j.get<long long>();
  if (v < lo || v > hi)
    fail(pointer, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + brief(j));
  return v;
}

std::uint64_t get_uint64(const json& j, const std::string& pointer) {
  if (j.is_number_unsigned()) return j.get<std::uint64_t>();
  if (j.is_number_integer() && j.get<std::int64_t>() >= 0) return std::uint64_t(j.get<std::int64_t>());
  fail(pointer, "must be an integer in [0, 18446744073709551615], got " + brief(j));
}

std::vector<json> parse_knob_values(const json& j, const std::string& pointer) {
  std::vector<json> values;
  std::set<json> seen;
  auto add = [&](const json& v, const std::string& p) {
    if (!v.is_number() && !v.is_string() && !v.is_boolean())
      fail(p, "knob value must be a number, string or boolean, got " + brief(v));
    if (seen.insert(v).second) values.push_back(v);
  };
  if (j.is_array()) {
    if (j.empty()) fail(pointer, "must list at least one value");
    if (j.size() > kMaxKnobValues)
      fail(pointer, "must list at most " + std::to_string(kMaxKnobValues) + " values, got " + std::to_string(j.size()));
    for (std::size_t i = 0; i < j.size(); ++i) add(j[i], child(pointer, i));
  } else {
    add(j, pointer);
  }
  return values;
}

std::string default_scene_name(const SceneSpec& s) {
  if (s.source == SceneSource::File) return std::filesystem::path(s.file).stem().string();
  const std::string base = s.model.empty() ? s.generator
                                           : s.generator + "-" + std::filesystem::path(s.model).stem().string();
  return s.count ? base + "-" + std::to_string(*s.count) : base;
}

SceneSpec parse_scene(const json& j, const std::string& pointer) {
  if (j.is_string()) {
    try {
      return parse_scene_item(j.get<std::string>());
    } catch (const SweepError& e) {
      fail(pointer, e.what());
    }
  }
  if (!j.is_object()) fail(pointer, "a scene must be a string or an object, got " + brief(j));
  require_keys(j, pointer, {"name", "generator", "seed", "count", "model", "file"});
  SceneSpec s;
  const bool has_gen = j.contains("generator"), has_file = j.contains("file");
  if (has_gen == has_file) fail(pointer, "a scene needs exactly one of 'generator' or 'file'");
  if (has_file) {
    s.source = SceneSource::File;
    s.file = get_string(j["file"], child(pointer, "file"));
    if (s.file.empty()) fail(child(pointer, "file"), "must not be empty");
    for (const char* k : {"seed", "count", "model"})
      if (j.contains(k)) fail(child(pointer, k), "only generator scenes take this key");
  } else {
    s.generator = get_string(j["generator"], child(pointer, "generator"));
    if (s.generator.empty()) fail(child(pointer, "generator"), "must not be empty");
    if (j.contains("seed")) s.seed = get_uint64(j["seed"], child(pointer, "seed"));
    if (j.contains("count")) s.count = int(get_integer(j["count"], child(pointer, "count"), 0, scenes_gen::kMaxCount));
    if (j.contains("model")) {
      s.model = get_string(j["model"], child(pointer, "model"));
      if (s.model.empty()) fail(child(pointer, "model"), "must not be empty");
      if (!scenes_gen::generator_takes_model(s.generator))
        fail(child(pointer, "model"), "generator '" + s.generator + "' takes no model (only mesh and mesh_grid do)");
    }
  }
  s.name = j.contains("name") ? get_string(j["name"], child(pointer, "name")) : default_scene_name(s);
  if (s.name.empty()) fail(child(pointer, "name"), "must not be empty");
  return s;
}

StructureSpec parse_structure(const json& j, const std::string& pointer) {
  StructureSpec s;
  if (j.is_string()) {
    s.name = j.get<std::string>();
  } else if (j.is_object()) {
    if (!j.contains("name")) fail(pointer, "a structure needs a 'name'");
    s.name = get_string(j["name"], child(pointer, "name"));
    for (const auto& [key, value] : j.items())
      if (key != "name") s.knobs[key] = parse_knob_values(value, child(pointer, key));
  } else {
    fail(pointer, "a structure must be a name or an object, got " + brief(j));
  }
  if (s.name.empty()) fail(pointer, "structure name must not be empty");
  return s;
}

KnobValues parse_knobs(const json& j, const std::string& pointer) {
  if (!j.is_object()) fail(pointer, "must be an object of knob -> value(s), got " + brief(j));
  KnobValues knobs;
  for (const auto& [key, value] : j.items()) knobs[key] = parse_knob_values(value, child(pointer, key));
  return knobs;
}

/// Integrator knob groups: an object (one group) or a non-empty array of objects. Every knob must
/// be one the integrator has, and every value one it accepts.
std::vector<KnobValues> parse_integrator_knobs(const json& j, const std::string& pointer,
                                               const std::string& integrator_name) {
  const tracer::Integrator& integrator = integrators::named(integrator_name, "integrator");
  const json known = integrator.params(json::object());
  auto group = [&](const json& g, const std::string& p) {
    KnobValues knobs = parse_knobs(g, p);
    for (const auto& [k, values] : knobs) {
      if (!known.contains(k)) {
        std::string names;
        for (const auto& [name, v] : known.items()) names += (names.empty() ? "" : ", ") + name;
        fail(child(p, k), "integrator " + integrator_name + " has no knob '" + k + "' (its knobs: " +
                              (names.empty() ? "none" : names) + ")");
      }
      for (std::size_t i = 0; i < values.size(); ++i) {
        try {
          integrator.params(json{{k, values[i]}});
        } catch (const std::exception& e) {
          fail(child(child(p, k), i), e.what());
        }
      }
    }
    if (knobs.empty()) fail(p, "must name at least one integrator knob");
    return knobs;
  };
  std::vector<KnobValues> groups;
  if (j.is_array()) {
    if (j.empty()) fail(pointer, "must list at least one group of knobs");
    for (std::size_t i = 0; i < j.size(); ++i) groups.push_back(group(j[i], child(pointer, i)));
  } else {
    groups.push_back(group(j, pointer));
  }
  return groups;
}

json knobs_to_json(const KnobValues& knobs) {
  json j = json::object();
  for (const auto& [k, v] : knobs) j[k] = v;
  return j;
}

std::string join(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : ", ") + s;
  return out;
}

}  // namespace

std::pair<int, int> parse_resolution(const std::string& text, const std::string& what) {
  const auto x = text.find('x');
  int w = 0, h = 0;
  const char* end = text.data() + text.size();
  const bool ok = x != std::string::npos &&
                  std::from_chars(text.data(), text.data() + x, w).ptr == text.data() + x &&
                  std::from_chars(text.data() + x + 1, end, h).ptr == end;
  if (!ok || w <= 0 || h <= 0 || w > 65536 || h > 65536)
    throw SweepError(what + ": expected WIDTHxHEIGHT with both in [1, 65536], got '" + text + "'");
  return {w, h};
}

SceneSpec parse_scene_item(const std::string& item) {
  if (item.empty()) throw SweepError("empty scene name");
  SceneSpec s;
  const auto colon = item.find(':');
  const bool looks_like_file = item.find('/') != std::string::npos || item.find('.') != std::string::npos;
  if (looks_like_file && colon == std::string::npos) {
    s.source = SceneSource::File;
    s.file = item;
  } else if (colon != std::string::npos) {
    s.generator = item.substr(0, colon);
    const std::string text = item.substr(colon + 1);
    int count = -1;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), count);
    s.count = count;
    if (s.generator.empty() || r.ptr != text.data() + text.size() || r.ec != std::errc() || count < 0)
      throw SweepError("scene '" + item + "': expected GENERATOR, GENERATOR:COUNT or a scene file path");
  } else {
    s.generator = item;
  }
  s.name = default_scene_name(s);
  return s;
}

std::optional<std::vector<std::string>> structure_knobs(const std::string& structure) {
  return accel::knob_names(structure);
}

SweepDefinition parse_sweep_definition(const json& j) {
  if (!j.is_object()) fail("", "a sweep definition must be a JSON object");
  require_keys(j, "", {"name", "description", "scenes", "structures", "knobs", "resolution", "threads",
                       "repetitions", "warmup", "max_memory_bytes", "integrator", "mode", "validate_resolution",
                       "integrator_knobs", "fronts", "noise_threshold", "remeasure", "images"});
  SweepDefinition d;
  if (j.contains("name")) {
    d.name = get_string(j["name"], "/name");
    const bool safe = !d.name.empty() && std::all_of(d.name.begin(), d.name.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
    });
    if (!safe) fail("/name", "must be a non-empty file-name-safe word ([A-Za-z0-9._-]), got " + brief(j["name"]));
  }
  if (j.contains("description")) d.description = get_string(j["description"], "/description");

  if (!j.contains("scenes")) fail("/scenes", "missing (list the scenes to sweep)");
  if (!j["scenes"].is_array() || j["scenes"].empty()) fail("/scenes", "must be a non-empty array");
  std::set<std::string> scene_names;
  for (std::size_t i = 0; i < j["scenes"].size(); ++i) {
    d.scenes.push_back(parse_scene(j["scenes"][i], child("/scenes", i)));
    if (!scene_names.insert(d.scenes.back().name).second)
      fail(child("/scenes", i), "scene name '" + d.scenes.back().name + "' is used twice; give one a 'name'");
  }

  if (!j.contains("structures")) fail("/structures", "missing (list the structures to sweep)");
  if (!j["structures"].is_array() || j["structures"].empty()) fail("/structures", "must be a non-empty array");
  for (std::size_t i = 0; i < j["structures"].size(); ++i)
    d.structures.push_back(parse_structure(j["structures"][i], child("/structures", i)));

  if (j.contains("knobs")) d.knobs = parse_knobs(j["knobs"], "/knobs");
  if (j.contains("resolution")) {
    const json& r = j["resolution"];
    if (r.is_string()) {
      std::tie(d.width, d.height) = parse_resolution(r.get<std::string>(), "/resolution");
    } else if (!(r.is_number_integer() && r.get<long long>() == 0)) {
      fail("/resolution", "must be \"WIDTHxHEIGHT\" or 0 for each scene's own, got " + brief(r));
    }
  }
  // "mode" is the key's older name, kept so that earlier sweep and results files still parse.
  if (j.contains("integrator") && j.contains("mode")) fail("/mode", "give \"integrator\" or its older name \"mode\", not both");
  for (const char* key : {"integrator", "mode"}) {
    if (!j.contains(key)) continue;
    const std::string where = std::string("/") + key;
    d.integrator = get_string(j[key], where);
    if (!integrators::find(d.integrator))
      fail(where, "unknown integrator " + brief(j[key]) + " (known: " + integrators::names() + ")");
  }
  if (j.contains("integrator_knobs"))
    d.integrator_knobs = parse_integrator_knobs(j["integrator_knobs"], "/integrator_knobs", d.integrator);
  if (j.contains("images")) {
    if (!j["images"].is_boolean()) fail("/images", "must be true or false, got " + brief(j["images"]));
    d.save_images = j["images"].get<bool>();
  }
  if (j.contains("fronts")) {
    if (!j["fronts"].is_object()) fail("/fronts", "must be an object, got " + brief(j["fronts"]));
    d.fronts = j["fronts"];
  }
  if (j.contains("validate_resolution")) {
    const json& r = j["validate_resolution"];
    if (r.is_string()) {
      std::tie(d.validate_width, d.validate_height) =
          parse_resolution(r.get<std::string>(), "/validate_resolution");
    } else if (!(r.is_number_integer() && r.get<long long>() == 0)) {
      fail("/validate_resolution", "must be \"WIDTHxHEIGHT\" or 0 for the timed resolution, got " + brief(r));
    }
    // Validating at the timed resolution is the ordinary sweep: normalise it away.
    if (d.validate_width == d.width && d.validate_height == d.height) d.validate_width = d.validate_height = 0;
  }
  if (j.contains("threads")) d.threads = int(get_integer(j["threads"], "/threads", 0, 4096));
  if (j.contains("repetitions")) d.repetitions = int(get_integer(j["repetitions"], "/repetitions", 1, 10000));
  if (j.contains("warmup")) d.warmup = int(get_integer(j["warmup"], "/warmup", 0, 10000));
  if (j.contains("noise_threshold")) {
    const json& t = j["noise_threshold"];
    if (!t.is_number() || !(t.get<double>() >= 0.0 && t.get<double>() <= 10.0))
      fail("/noise_threshold", "must be a number in [0, 10] (a fraction of the value), got " + brief(t));
    d.noise_threshold = t.get<double>();
  }
  if (j.contains("remeasure")) d.remeasure = int(get_integer(j["remeasure"], "/remeasure", 0, 100));
  if (j.contains("max_memory_bytes"))
    d.max_memory_bytes = std::uint64_t(
        get_integer(j["max_memory_bytes"], "/max_memory_bytes", 0, std::numeric_limits<long long>::max()));

  // Catch misspelt knobs before a long run, with the knob table's own message: a knob must
  // belong to a structure that is swept. A bad value is the factory's business: its row fails
  // with the same one-line message and the sweep goes on.
  std::set<std::string> all_knobs;
  for (std::size_t i = 0; i < d.structures.size(); ++i) {
    const auto& s = d.structures[i];
    const std::string at = child("/structures", i);
    const auto knobs = structure_knobs(s.name);
    if (!knobs) fail(child(at, "name"), "unknown structure '" + s.name + "' (known: " + join(accel::accel_names()) + ")");
    all_knobs.insert(knobs->begin(), knobs->end());
    for (const auto& [k, values] : s.knobs) {
      (void)values;
      try {
        accel::check_knob_name(s.name, k);
      } catch (const knobs::ConfigError& e) {
        fail(child(at, k), e.what());
      }
    }
  }
  for (const auto& [k, v] : d.knobs) {
    (void)v;
    if (!all_knobs.count(k)) fail(child("/knobs", k), "no structure in this sweep has the knob '" + k + "'");
  }

  // Refuse a sweep too large to list before anything expands it (a typo such as a
  // million-value axis crossed with another).
  double configs = 0.0;
  for (const auto& s : d.structures) {
    const auto has = structure_knobs(s.name);
    double n = 1.0;
    for (const auto& [k, values] : s.knobs) n *= double(values.size());
    if (has)
      for (const auto& [k, values] : d.knobs)
        if (!s.knobs.count(k) && std::find(has->begin(), has->end(), k) != has->end()) n *= double(values.size());
    configs += n;
  }
  double settings = 0.0;  // integrator settings: each group crossed, the groups joined
  for (const auto& g : d.integrator_knobs) {
    double n = 1.0;
    for (const auto& [k, values] : g) n *= double(values.size());
    settings += n;
  }
  configs *= double(d.scenes.size()) * std::max(settings, 1.0);
  if (configs > double(kMaxConfigurations)) {
    char text[64];
    std::snprintf(text, sizeof text, "%.3g", configs);
    fail("", std::string("the sweep expands to ") + text + " configurations, more than the limit of " +
                 std::to_string(kMaxConfigurations) + " (fewer knob values or scenes)");
  }
  return d;
}

SweepDefinition parse_sweep_text(std::string_view text, const std::string& name) {
  json j;
  try {
    j = input::parse_json(text);
  } catch (const input::InputError& e) {
    throw SweepError(name + ": " + e.what());
  }
  try {
    return parse_sweep_definition(j);
  } catch (const SweepError& e) {
    throw SweepError(name + ": " + e.what());
  }
}

std::string read_input_file(const std::string& path, std::uint64_t max_bytes, std::string_view what) {
  try {
    return input::read_file(path, max_bytes, what);
  } catch (const input::InputError& e) {
    throw SweepError(e.what());
  }
}

SweepDefinition load_sweep_file(const std::string& path) {
  return parse_sweep_text(read_input_file(path, input::kMaxSweepFileBytes, "sweep file"), path);
}

json to_json(const SceneSpec& s) {
  json j = {{"name", s.name}};
  if (s.source == SceneSource::File) {
    j["file"] = s.file;
  } else {
    j["generator"] = s.generator;
    j["seed"] = s.seed;
    if (s.count) j["count"] = *s.count;
    if (!s.model.empty()) j["model"] = s.model;
  }
  return j;
}

json to_json(const SweepDefinition& d) {
  json scenes = json::array(), structures = json::array();
  for (const auto& s : d.scenes) scenes.push_back(to_json(s));
  for (const auto& s : d.structures) {
    json e = knobs_to_json(s.knobs);
    e["name"] = s.name;
    structures.push_back(e);
  }
  json j = {{"name", d.name},
          {"description", d.description},
          {"scenes", scenes},
          {"structures", structures},
          {"knobs", knobs_to_json(d.knobs)},
          {"resolution", d.width ? json(std::to_string(d.width) + "x" + std::to_string(d.height)) : json(0)},
          {"threads", d.threads},
          {"repetitions", d.repetitions},
          {"warmup", d.warmup},
          {"max_memory_bytes", d.max_memory_bytes}};
  // Defaults are left out so that definitions written before these keys existed still match.
  if (d.integrator != "whitted") j["integrator"] = d.integrator;
  if (d.validates_apart())
    j["validate_resolution"] = std::to_string(d.validate_width) + "x" + std::to_string(d.validate_height);
  if (!d.integrator_knobs.empty()) {
    json groups = json::array();
    for (const auto& g : d.integrator_knobs) groups.push_back(knobs_to_json(g));
    j["integrator_knobs"] = groups;
  }
  if (!d.fronts.is_null()) j["fronts"] = d.fronts;
  if (d.noise_threshold != SweepDefinition{}.noise_threshold) j["noise_threshold"] = d.noise_threshold;
  if (d.remeasure != SweepDefinition{}.remeasure) j["remeasure"] = d.remeasure;
  if (d.save_images) j["images"] = true;
  return j;
}

std::string config_key(const std::string& scene, const std::string& structure, const json& params,
                       const json& integrator_params) {
  // nlohmann::json objects keep keys sorted, so dump() is canonical.
  // Invalid UTF-8 in a knob string (from a flag) is replaced, never thrown.
  const auto dump = [](const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); };
  std::string key = scene + "|" + structure + "|" + dump(params.is_null() ? json::object() : params);
  if (!integrator_params.is_null() && !integrator_params.empty()) key += "|" + dump(integrator_params);
  return key;
}

namespace {

/// Every combination of `knobs` (an odometer over the value lists in sorted knob order), as
/// objects; one empty object when there are no knobs.
std::vector<json> cross(const KnobValues& knobs) {
  std::vector<std::pair<std::string, const std::vector<json>*>> axes;
  for (const auto& [k, values] : knobs) axes.emplace_back(k, &values);
  std::vector<std::size_t> at(axes.size(), 0);
  std::vector<json> out;
  while (true) {
    json params = json::object();
    for (std::size_t a = 0; a < axes.size(); ++a) params[axes[a].first] = (*axes[a].second)[at[a]];
    out.push_back(std::move(params));
    // Advance the last axis, carrying into earlier ones; done when the first one wraps.
    bool wrapped = true;
    for (std::size_t a = axes.size(); a-- > 0;) {
      if (++at[a] < axes[a].second->size()) {
        wrapped = false;
        break;
      }
      at[a] = 0;
    }
    if (wrapped) break;
  }
  return out;
}

}  // namespace

std::vector<SweepConfig> expand(const SweepDefinition& d) {
  std::vector<SweepConfig> out;
  std::set<std::string> seen;
  // Knob sets are probed once per structure name.
  std::map<std::string, std::optional<std::vector<std::string>>> probed;
  for (const auto& s : d.structures)
    if (!probed.count(s.name)) probed[s.name] = structure_knobs(s.name);
  // The integrator settings: every group crossed, joined in group order, repeats dropped.
  std::vector<json> integrator_settings;
  std::set<json> seen_settings;
  for (const auto& g : d.integrator_knobs)
    for (json& ip : cross(g))
      if (seen_settings.insert(ip).second) integrator_settings.push_back(std::move(ip));
  if (integrator_settings.empty()) integrator_settings.push_back(json::object());

  for (std::size_t si = 0; si < d.scenes.size(); ++si) {
    for (const auto& s : d.structures) {
      KnobValues knobs = s.knobs;
      if (const auto& has = probed[s.name])
        for (const auto& [k, values] : d.knobs)
          if (!knobs.count(k) && std::find(has->begin(), has->end(), k) != has->end()) knobs[k] = values;
      for (const json& params : cross(knobs))
        for (const json& ip : integrator_settings) {
          std::string key = config_key(d.scenes[si].name, s.name, params, ip);
          if (seen.insert(key).second)
            out.push_back(SweepConfig{out.size(), si, s.name, params, ip, std::move(key)});
        }
    }
  }
  return out;
}

std::vector<SweepConfig> shard(const std::vector<SweepConfig>& all, int index, int count) {
  std::vector<SweepConfig> out;
  for (const auto& c : all)
    if (int(c.index % std::size_t(count)) == index) out.push_back(c);
  return out;
}

std::pair<int, int> parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  int i = -1, n = 0;
  const char* end = text.data() + text.size();
  const bool ok = slash != std::string::npos &&
                  std::from_chars(text.data(), text.data() + slash, i).ptr == text.data() + slash &&
                  std::from_chars(text.data() + slash + 1, end, n).ptr == end;
  if (!ok || n < 1 || i < 0 || i >= n)
    throw SweepError("--shard: expected I/N with 0 <= I < N, got '" + text + "'");
  return {i, n};
}

}  // namespace harness
