#pragma once
// What a sweep measures: scenes x structures x knob values, plus the measurement settings.
// Parsed from a sweep JSON file (sweeps/*.json) with every key checked, and expanded into the
// ordered list of configurations that the runner measures and the results file records.

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace harness {

/// A malformed sweep definition or flag; what() is one line naming the JSON pointer or flag.
struct SweepError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The text of `path` read by input::read_file (a regular file of at most `max_bytes`; `what`
/// names the kind of file), its errors as SweepError.
std::string read_input_file(const std::string& path, std::uint64_t max_bytes, std::string_view what);

/// Where a scene comes from.
enum class SceneSource { Generator, File };

/// One scene of a sweep: a scenes_gen generator with options, or a scene file (.json, .nff).
struct SceneSpec {
  std::string name;                 ///< Unique label used in rows and keys.
  SceneSource source = SceneSource::Generator;  ///< Generator or file.
  std::string generator;            ///< Generator name (source Generator).
  std::uint64_t seed = 1;           ///< Generator seed (source Generator).
  std::optional<int> count;         ///< Generator size knob; unset = its default (source Generator).
  std::string model;                ///< Model of the mesh generators (source Generator); "" = theirs.
  std::string file;                 ///< Scene file path (source File).

  /// Family the scaling plot groups by: the generator name, or "file".
  std::string family() const { return source == SceneSource::Generator ? generator : "file"; }
};

/// Knob name -> the values to cross; each value is passed to accel::make_accel as given.
using KnobValues = std::map<std::string, std::vector<nlohmann::json>>;

/// One structure entry: a factory name and the knob values given for it alone.
struct StructureSpec {
  std::string name;   ///< accel::make_accel name.
  KnobValues knobs;   ///< Per-entry knob values; they win over the sweep-wide ones.
};

/// A whole sweep, normalised (every default spelled out) so that two equal sweeps compare equal.
struct SweepDefinition {
  std::string name = "sweep";           ///< Short name; default output is results/<name>.json.
  std::string description;              ///< Free text for the reader of the results.
  std::vector<SceneSpec> scenes;        ///< Scenes, in run order.
  std::vector<StructureSpec> structures;///< Structures, in run order.
  KnobValues knobs;                     ///< Sweep-wide knob values, applied to every structure that has the knob.
  int width = 0;                        ///< Image width, pixels; 0 = each scene's own.
  int height = 0;                       ///< Image height, pixels; 0 = each scene's own.
  std::string integrator = "whitted";   ///< Integrator of every configuration (integrators/integrators.h).
  /// The integrator's knobs to vary, as groups: each group's knobs are crossed with each other,
  /// and the groups are joined (one group per knob varies one knob at a time). Empty: the
  /// integrator's defaults only. JSON key "integrator_knobs": one object or an array of them.
  std::vector<KnobValues> integrator_knobs;
  bool save_images = false;             ///< Write each row's image as PNG (key "images").
  /// What `accelbench fronts` adds to a sweep (reference, metric, seeds); null for a plain sweep.
  /// Kept here so that --resume refuses a file written with other front settings.
  nlohmann::json fronts;
  int validate_width = 0;               ///< Width naive is rendered and compared at; 0 = the timed width.
  int validate_height = 0;              ///< Height naive is rendered and compared at; 0 = the timed height.

  /// True when naive is rendered (and structures checked) at a resolution of its own, not the timed one.
  bool validates_apart() const { return validate_width != 0; }
  int threads = 1;                      ///< Render threads; 0 = all cores.
  int repetitions = 5;                  ///< Timed renders per configuration (the median is reported).
  int warmup = 1;                       ///< Untimed renders before the timed ones.
  std::uint64_t max_memory_bytes = 0;   ///< Build memory budget, bytes; 0 = 25% of RAM.
  /// A row is noisy when its 95% interval (of the speedup; naive's and rows without a speedup:
  /// of the median time) is wider than this fraction of its value (0.10: wider than +-5%).
  double noise_threshold = 0.10;
  /// Passes of `repetitions` more interleaved rounds (with naive) that noisy rows get, at most.
  int remeasure = 2;
};

/// One measured unit: a structure with exact requested knobs on one scene.
struct SweepConfig {
  std::size_t index = 0;        ///< Position in the full (unsharded) configuration list.
  std::size_t scene = 0;        ///< Index into SweepDefinition::scenes.
  std::string structure;        ///< Factory name.
  nlohmann::json params;        ///< Requested knobs (an object; empty for naive or defaults).
  /// Requested integrator knobs (an object; empty = the integrator's defaults).
  nlohmann::json integrator_params = nlohmann::json::object();
  std::string key;              ///< Canonical key: equal keys are the same configuration.
};

/// Most values one knob axis may list in a sweep definition.
inline constexpr std::size_t kMaxKnobValues = 10'000;
/// Most configurations a sweep definition may expand to (the paper sweep has 230).
inline constexpr std::size_t kMaxConfigurations = 100'000;

/// Parses and validates a sweep definition; errors name the JSON pointer, e.g.
/// "/structures/2/max_depth/1: must be an integer, got \"8\"".
SweepDefinition parse_sweep_definition(const nlohmann::json& j);

/// Parses the text of a sweep file (input::parse_json: nesting limit, no duplicate keys);
/// errors start with `name`.
SweepDefinition parse_sweep_text(std::string_view text, const std::string& name);

/// Reads (a regular file within input::kMaxSweepFileBytes) and parses a sweep file; errors
/// start with the path.
SweepDefinition load_sweep_file(const std::string& path);

/// The normalised JSON form (parse_sweep_definition(to_json(d)) == d).
nlohmann::json to_json(const SweepDefinition& d);
nlohmann::json to_json(const SceneSpec& s);

/// Parses a --scenes item: a generator name, "generator:count", or a path to a scene file.
SceneSpec parse_scene_item(const std::string& item);

/// Canonical configuration key: scene name, structure and the sorted requested knobs, then the
/// sorted integrator knobs when there are any (so keys without them are as they always were).
std::string config_key(const std::string& scene, const std::string& structure,
                       const nlohmann::json& params,
                       const nlohmann::json& integrator_params = nlohmann::json::object());

/// Knob names a structure accepts, from its knob table in the registry (also for a structure
/// compiled out of this build); nullopt for an unknown name.
std::optional<std::vector<std::string>> structure_knobs(const std::string& structure);

/// Parses "WxH" (both > 0); throws SweepError naming `what`.
std::pair<int, int> parse_resolution(const std::string& text, const std::string& what);

/// Every configuration: scenes x structures x (knobs the structure has) x (each integrator knob
/// group crossed), naive once per scene and integrator setting. Knobs a structure lacks are not
/// crossed for it; duplicates are dropped.
std::vector<SweepConfig> expand(const SweepDefinition& d);

/// Shard i of n (0-based): the configurations whose index is i modulo n. Disjoint, and their
/// union over i is the whole list.
std::vector<SweepConfig> shard(const std::vector<SweepConfig>& all, int index, int count);

/// Parses "i/n" with 0 <= i < n; throws SweepError naming --shard.
std::pair<int, int> parse_shard(const std::string& text);

}  // namespace harness
