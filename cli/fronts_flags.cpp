#include "cli/fronts_flags.h"

#include "harness/accuracy_knobs.h"
#include "integrators/integrators.h"
#include "harness/sweep_definition.h"
#include "harness/sweep_results.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>

namespace cli {

using namespace harness;  // the command line drives the harness


namespace {

using nlohmann::json;

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t at = text.find(sep, start);
    out.push_back(text.substr(start, at == std::string::npos ? std::string::npos : at - start));
    if (at == std::string::npos) break;
    start = at + 1;
  }
  return out;
}

/// A value as the command line gives it: a JSON number or boolean when it reads as one, else the
/// text as a string (the integrator then checks it).
json value_from_text(const std::string& text) {
  // Arrays and objects are neither: never parsed, so deep nesting cannot cost a deep recursion
  // (destroying a parsed value recurses once per level).
  const auto first = text.find_first_not_of(" \t\n\r");
  if (first == std::string::npos || text[first] == '[' || text[first] == '{') return text;
  const json v = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (v.is_number() || v.is_boolean()) return v;
  return text;
}

/// "KNOB=REST"; throws naming the flag.
std::pair<std::string, std::string> assignment(const std::string& text, const std::string& flag) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw SweepError(flag + ": expected KNOB=VALUE, got '" + text + "'");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

bool is_integer_text(const std::string& s) {
  return !s.empty() && std::all_of(s.begin() + (s[0] == '-' ? 1 : 0), s.end(),
                                   [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

double number(const std::string& s, const std::string& flag) {
  double v = 0.0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v))
    throw SweepError(flag + ": '" + s + "' is not a number");
  return v;
}

/// The smallest error on the fronts of the results file at `path` in `metric`; throws naming
/// --floor-target-from.
double floor_target_from(const std::string& path, const std::string& metric) {
  const std::string flag = "--floor-target-from " + path;
  json results;
  try {
    results = read_results_file(path);
  } catch (const std::exception& e) {
    throw SweepError(flag + ": " + e.what());
  }
  double smallest = std::numeric_limits<double>::infinity();
  for (const json& front : results.value("fronts", json::array())) {
    if (front.value("metric", "") != metric)
      throw SweepError(flag + ": its fronts are in " + front.value("metric", "?") + ", not --metric " + metric);
    const json& e = front.value("smallest_error", json());
    if (e.is_number() && e.get<double>() > 0.0) smallest = std::min(smallest, e.get<double>());
  }
  if (!std::isfinite(smallest)) throw SweepError(flag + ": the file has no front with a non-zero error");
  return smallest;
}

}  // namespace

std::vector<json> parse_knob_values_text(const std::string& text, const std::string& flag) {
  if (text.empty()) throw SweepError(flag + ": empty range");
  std::vector<json> out;
  const std::vector<std::string> range = split(text, ':');
  if (range.size() == 3) {
    const double lo = number(range[0], flag), hi = number(range[1], flag);
    int n = 0;
    const auto r = std::from_chars(range[2].data(), range[2].data() + range[2].size(), n);
    if (r.ec != std::errc() || r.ptr != range[2].data() + range[2].size() || n < 1 || n > 1000)
      throw SweepError(flag + ": LO:HI:N needs N in [1, 1000], got '" + range[2] + "'");
    if (!(lo > 0.0) || !(hi >= lo))
      throw SweepError(flag + ": a log-spaced range LO:HI:N needs 0 < LO <= HI, got '" + text + "'");
    const bool integers = is_integer_text(range[0]) && is_integer_text(range[1]);
    // Integers up to 2^53: every one is exact as a double, and llround cannot overflow.
    if (integers && hi > 9007199254740992.0)
      throw SweepError(flag + ": an integer range LO:HI:N needs HI <= 2^53, got '" + range[1] + "'");
    for (int i = 0; i < n; ++i) {
      const double t = n == 1 ? 0.0 : double(i) / double(n - 1);
      const double v = lo * std::pow(hi / lo, t);
      json value;
      if (integers) {
        value = static_cast<long long>(std::llround(v));
      } else {
        // Four significant digits: a readable value that still sits on the log scale.
        const double scale = std::pow(10.0, 3 - std::floor(std::log10(v)));
        value = std::round(v * scale) / scale;
      }
      if (std::find(out.begin(), out.end(), value) == out.end()) out.push_back(value);
    }
    return out;
  }
  if (range.size() != 1) throw SweepError(flag + ": expected v1,v2,... or LO:HI:N, got '" + text + "'");
  for (const std::string& item : split(text, ',')) {
    if (item.empty()) throw SweepError(flag + ": empty value in '" + text + "'");
    const json v = value_from_text(item);
    if (std::find(out.begin(), out.end(), v) == out.end()) out.push_back(v);
  }
  return out;
}

void add_fronts_flags(CLI::App& cmd, FrontsFlags& f) {
  cmd.add_option("scenes", f.scenes, "Scenes: generator, generator:count, or scene file (.json, .nff)")->required();
  cmd.add_option("--knobs", f.knobs,
                 "Knobs to vary, comma-separated, one at a time; a*b varies a and b jointly (whitted: " +
                     accuracy_knob_names("whitted") + ")")
      ->required();
  cmd.add_flag("--joint", f.joint, "Vary every listed knob jointly (their cross product)");
  cmd.add_option("--values", f.values, "KNOB=v1,v2,... or KNOB=LO:HI:N (log-spaced); default: the knob's range");
  cmd.add_option("--set", f.set, "KNOB=VALUE held in every render and in the references");
  cmd.add_option("--reference-set", f.reference_set,
                 "KNOB=VALUE of the reference integrator over its recipe (e.g. passes=64 for a cheaper ppm reference)");
  cmd.add_option("--integrator", f.integrator, "Integrator whose knobs are studied: " + integrators::names())
      ->capture_default_str();
  cmd.add_option("--accel", f.accel, "Structure every render goes through")->capture_default_str();
  cmd.add_option("--resolution", f.resolution, "Image size WIDTHxHEIGHT")->capture_default_str();
  cmd.add_option("--validate-resolution", f.validate_resolution,
                 "Check every configuration against naive at WIDTHxHEIGHT (0: at the timed resolution)")
      ->capture_default_str();
  cmd.add_option("--metric", f.metric, "Error of the front and of tune: rmse or rel_mse")->capture_default_str();
  cmd.add_option("--epsilon", f.epsilon, "Epsilon of the relative MSE, (x-r)^2/(r^2+eps)")->capture_default_str();
  cmd.add_option("--seeds", f.seeds, "Renders per configuration for the bias/variance split (1: none)")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  cmd.add_option("--threads", f.threads, "Threads of the timed renders (0 = all cores)")->check(CLI::Range(0, 4096))
      ->capture_default_str();
  cmd.add_option("--repetitions", f.repetitions, "Timed renders per configuration (median reported)")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  cmd.add_option("--warmup", f.warmup, "Untimed renders before the timed ones")->check(CLI::Range(0, 10000))
      ->capture_default_str();
  cmd.add_option("--reference-threads", f.reference_threads, "Threads of the reference renders (0 = all cores)")
      ->check(CLI::Range(0, 4096));
  cmd.add_option("--cache", f.cache, "Reference cache directory (default " + default_reference_cache() + ")");
  cmd.add_flag("--no-cache", f.no_cache, "Neither read nor write cached references");
  cmd.add_flag("--refresh-reference", f.refresh, "Render the references again and overwrite the cache");
  cmd.add_option("--name", f.name, "Name of the run; default output results/<name>.json (default fronts-SCENE)");
  cmd.add_option("--seed", f.seed, "Generator seed of generated scenes")->capture_default_str();
  cmd.add_option("--estimator", f.estimator,
                 "How a progressive reference (ppm) combines its stages: plain, or richardson (its leading bias cancelled)")
      ->capture_default_str();
  cmd.add_option("--floor-target", f.floor_target,
                 "Stopping rule of progressive references: 8x the passes, level after level, until the floor (in --metric) "
                 "is at most this (0: the recipe's passes only)")
      ->check(CLI::Range(0.0, std::numeric_limits<double>::max()));
  cmd.add_option("--floor-target-from", f.floor_target_from,
                 "Results file of an earlier run of the fronts: the target is its smallest error over --floor-ratio");
  cmd.add_option("--floor-ratio", f.floor_ratio, "How far below the smallest error the floor should lie")
      ->check(CLI::Range(1.0, 1e6))
      ->capture_default_str();
  cmd.add_option("--reference-time-limit", f.reference_time_limit,
                 "Rendering time one reference's levels may take under the stopping rule, s")
      ->check(CLI::Range(0.0, 1e7))
      ->capture_default_str();
}

FrontsRequest request_from_flags(const FrontsFlags& f) {
  FrontsRequest r;
  for (const std::string& item : f.scenes) {
    try {
      r.scenes.push_back(parse_scene_item(item));
    } catch (const SweepError& e) {
      throw SweepError(std::string("SCENE: ") + e.what());
    }
    std::uint64_t seed = 0;
    const auto p = std::from_chars(f.seed.data(), f.seed.data() + f.seed.size(), seed);
    if (p.ec != std::errc() || p.ptr != f.seed.data() + f.seed.size())
      throw SweepError("--seed: expected an integer in [0, 2^64-1], got '" + f.seed + "'");
    r.scenes.back().seed = seed;
  }
  r.integrator = integrators::named(f.integrator, "--integrator").name;
  r.structure = f.accel;
  if (f.knobs.empty()) throw SweepError("--knobs: name at least one knob");
  std::vector<std::string> all;
  for (const std::string& g : split(f.knobs, ',')) {
    if (g.empty()) throw SweepError("--knobs: empty knob name in '" + f.knobs + "'");
    std::vector<std::string> group = split(g, '*');
    for (const auto& k : group)
      if (k.empty()) throw SweepError("--knobs: empty knob name in '" + f.knobs + "'");
    all.insert(all.end(), group.begin(), group.end());
    r.groups.push_back(std::move(group));
  }
  if (f.joint) r.groups = {all};
  for (const std::string& v : f.values) {
    const auto [knob, list] = assignment(v, "--values");
    if (r.values.count(knob)) throw SweepError("--values: knob '" + knob + "' is given twice");
    r.values[knob] = parse_knob_values_text(list, "--values " + knob);
  }
  for (const std::string& s : f.set) {
    const auto [knob, value] = assignment(s, "--set");
    if (value.empty()) throw SweepError("--set: knob '" + knob + "' has no value");
    r.settings.fixed[knob] = value_from_text(value);
  }
  for (const std::string& s : f.reference_set) {
    const auto [knob, value] = assignment(s, "--reference-set");
    if (value.empty()) throw SweepError("--reference-set: knob '" + knob + "' has no value");
    r.settings.reference[knob] = value_from_text(value);
  }
  if (f.metric == "rmse") r.settings.metric = FrontMetric::Rmse;
  else if (f.metric == "rel_mse") r.settings.metric = FrontMetric::RelMse;
  else throw SweepError("--metric: must be rmse or rel_mse, got '" + f.metric + "'");
  if (!(f.epsilon > 0.0) || !std::isfinite(f.epsilon))
    throw SweepError("--epsilon: must be > 0, got " + std::to_string(f.epsilon));
  r.settings.epsilon = f.epsilon;
  r.settings.seeds = f.seeds;
  try {
    r.settings.estimator = parse_estimator(f.estimator);
  } catch (const std::invalid_argument& e) {
    throw SweepError(std::string("--estimator: ") + e.what());
  }
  std::tie(r.width, r.height) = parse_resolution(f.resolution, "--resolution");
  if (f.validate_resolution == "0") {
    r.validate_width = r.validate_height = 0;
  } else {
    std::tie(r.validate_width, r.validate_height) = parse_resolution(f.validate_resolution, "--validate-resolution");
  }
  r.threads = f.threads;
  r.repetitions = f.repetitions;
  r.warmup = f.warmup;
  if (!f.name.empty()) {
    r.name = f.name;
  } else {
    std::string name = "fronts";
    for (const auto& s : r.scenes) name += "-" + s.name;
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
    r.name = r.scenes.size() <= 3 ? name : "fronts";
  }
  return r;
}

ReferenceOptions reference_options_from_flags(const FrontsFlags& f) {
  ReferenceOptions o;
  o.cache_dir = f.no_cache ? "" : f.cache.empty() ? default_reference_cache() : f.cache;
  o.refresh = f.refresh;
  o.threads = f.reference_threads;
  o.epsilon = f.epsilon;
  if (f.validate_resolution != "0")
    std::tie(o.validate_width, o.validate_height) = parse_resolution(f.validate_resolution, "--validate-resolution");
  o.time_limit_s = f.reference_time_limit;
  o.floor_target = f.floor_target;
  if (!f.floor_target_from.empty()) {
    if (f.floor_target > 0.0) throw SweepError("--floor-target-from: give it or --floor-target, not both");
    o.floor_target = floor_target_from(f.floor_target_from, f.metric) / f.floor_ratio;
  }
  return o;
}

void print_fronts(const json& results, std::FILE* out) {
  if (!results.contains("fronts")) return;
  for (const json& front : results["fronts"]) {
    const std::string scene = front["scene"], name = front["front"], metric = front["metric"];
    const json& ref = front["reference"];
    std::string made_by = ref["integrator"].get<std::string>() + " " + ref["params"].dump();
    if (ref.contains("analytic")) made_by = "the " + ref["analytic"].get<std::string>() + "'s closed form";
    if (ref.contains("stopping"))
      made_by += " (stopping rule: " + ref["stopping"].value("stopped_by", std::string("?")) + ")";
    std::fprintf(out, "\n%s, front %s: reference %s, floor %s %.3g\n", scene.c_str(), name.c_str(), made_by.c_str(),
                 metric.c_str(), front["floor"].get<double>());
    std::fprintf(out, "  %-28s %12s %12s %12s %12s %9s  %s\n", "knobs", "render ms", metric.c_str(), "bias", "noise",
                 "resolved", "front");
    for (const json& row : results["rows"]) {
      if (row.value("scene", "") != scene || row.value("front", "") != name) continue;
      std::string knobs = row.value("integrator_params", json::object()).dump();
      const json& e = row["error"][metric];
      const json bv = row.value("bias_variance", json::object());
      auto num = [](const json& v) {
        char buf[32];
        if (v.is_number()) std::snprintf(buf, sizeof buf, "%.4g", v.get<double>());
        else std::snprintf(buf, sizeof buf, "-");
        return std::string(buf);
      };
      std::fprintf(out, "  %-28s %12.3f %12s %12s %12s %9s  %s\n", knobs.c_str(),
                   row["render_ms"]["median"].get<double>(), num(e).c_str(), num(bv.value("bias", json())).c_str(),
                   num(bv.value("noise", json())).c_str(), row.value("resolved", true) ? "yes" : "no",
                   row.value("on_front", false) ? "*" : "");
    }
  }
}

}  // namespace cli
