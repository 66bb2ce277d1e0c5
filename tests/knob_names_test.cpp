// One knob system: every knob is spelled once, in its table. A knob name written as a string
// literal in library or command-line code outside the file that defines a table with it is a
// second spelling that can drift (a renamed knob, a flag that still sets the old one). This test
// reads the sources and fails on one; the few literals that share a knob's name but are not the
// knob (a results field, a scene file's own setting) are listed with the reason.

#include "accel/accel.h"
#include "integrators/integrators.h"
#include "photon/density.h"
#include "photon/knn.h"
#include "photon/photon_tree_params.h"
#include "tracer/scene.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>

namespace {

namespace fs = std::filesystem;

/// Every knob name of every table: the structures', the integrators', the photon maps' and the
/// scene file's render settings.
std::set<std::string> all_knob_names() {
  std::set<std::string> names;
  for (const accel::StructureInfo& s : accel::structures())
    for (const std::string& k : s.knobs) names.insert(k);
  for (const tracer::Integrator* i : integrators::all())
    for (const std::string& k : i->knob_table().names()) names.insert(k);
  for (const knobs::AnyKnobTable* t : std::initializer_list<const knobs::AnyKnobTable*>{
           &photon::PhotonTreeParams::knobs(), &photon::GatherParams::knobs(), &photon::DensityParams::knobs(),
           &tracer::RenderSettings::knobs()})
    for (const std::string& k : t->names()) names.insert(k);
  return names;
}

/// The source with // comments blanked (a comment may name a knob).
std::string code_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::string out, line;
  while (std::getline(in, line)) {
    // A "//" inside a string literal (a URL) is rare in this code; none names a knob.
    const auto c = line.find("//");
    out += (c == std::string::npos ? line : line.substr(0, c)) + "\n";
  }
  return out;
}

/// Library and command-line sources, relative to the repository.
std::map<std::string, std::string> sources() {
  std::map<std::string, std::string> out;
  const fs::path root = ACCELBENCH_SOURCE_DIR;
  for (const char* dir : {"knobs", "accel", "tracer", "photon", "scenes_gen", "input", "integrators", "harness", "cli", "bench"})
    for (const auto& e : fs::recursive_directory_iterator(root / dir)) {
      const std::string ext = e.path().extension().string();
      if (e.is_regular_file() && (ext == ".h" || ext == ".cpp"))
        out[fs::relative(e.path(), root).string()] = code_of(e.path());
    }
  return out;
}

/// Literals that share a knob's name without being the knob, by file, with why.
const std::map<std::pair<std::string, std::string>, const char*>& not_the_knob() {
  static const std::map<std::pair<std::string, std::string>, const char*> m = {
      {{"photon/photon_integrator.cpp", "max_radius"}, "the radius in effect, in the render statistics"},
      {{"photon/photon_integrator.cpp", "global_photons"}, "the memory-budget error names the knob to lower"},
      {{"photon/photon_integrator.cpp", "caustic_photons"}, "the memory-budget error names the knob to lower"},
      {{"harness/sweep_machine.cpp", "isa"}, "the machine's ISA in every results file"},
      {{"bench/validated_main.h", "isa"}, "the build's ISA in the benchmark context"},
      {{"harness/sweep_definition.cpp", "seed"}, "a generated scene's seed in a sweep file"},
      {{"harness/tune.cpp", "max_depth"}, "one of the tuner's two axes (TunePoint), each a knob of every tree"},
      {{"harness/tune.cpp", "max_leaf_size"}, "one of the tuner's two axes (TunePoint), each a knob of every tree"},
      {{"bench/bench_trace.cpp", "max_depth"}, "an axis of the depth x leaf-size benchmark grid"},
      {{"bench/bench_trace.cpp", "max_leaf_size"}, "an axis of the depth x leaf-size benchmark grid"},
      {{"tracer/scene_json.cpp", "triangle"}, "a scene file's triangle object, named in its messages"},
      {{"cli/cli_util.cpp", "triangle"}, "the word for one triangle in a scene's description"},
  };
  return m;
}

TEST(KnobNames, EveryKnobIsSpelledOnlyInItsTable) {
  const std::set<std::string> names = all_knob_names();
  ASSERT_GT(names.size(), 20u);
  const auto code = sources();
  // Where each name is defined: a knob factory call with it, a named constant holding it
  // (knobs::kSeedKnob, tracer::kPrecisionKnob) that the tables use, or a table that takes the
  // knob from a shared helper NAME_knob(&P::member) (placement_knob, precision_knob).
  std::map<std::string, std::set<std::string>> defined_in;
  const std::regex factory(R"re((?:K|Knob<\w+>)::(?:integer|number|number_or_auto|number_or_infinity|boolean|choice)\(\s*"(\w+)")re");
  const std::regex constant(R"re(inline constexpr const char\* k\w+Knob = "(\w+)";)re");
  const std::regex helper(R"re(\b(\w+)_knob\(&)re");
  for (const auto& [file, text] : code)
    for (const std::regex& re : {factory, constant, helper})
      for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it)
        defined_in[(*it)[1]].insert(file);
  for (const std::string& n : names)
    EXPECT_TRUE(defined_in.count(n)) << "knob '" << n << "' is in a table but no table source spells it: the scan is stale";

  std::set<std::pair<std::string, std::string>> exemptions_used;
  for (const auto& [file, text] : code)
    for (const std::string& n : names) {
      if (defined_in[n].count(file)) continue;
      const std::string literal = "\"" + n + "\"";
      for (auto at = text.find(literal); at != std::string::npos; at = text.find(literal, at + 1)) {
        if (not_the_knob().count({file, n})) {
          exemptions_used.insert({file, n});
          continue;
        }
        const auto line = 1 + std::count(text.begin(), text.begin() + long(at), '\n');
        ADD_FAILURE() << file << ":" << line << ": the knob name " << literal
                      << " outside its table; read or write the knob through the table's struct";
      }
    }
  // An exemption nobody needs any more is removed, so the list stays true.
  for (const auto& [key, why] : not_the_knob())
    EXPECT_TRUE(exemptions_used.count(key)) << key.first << " no longer spells '" << key.second << "' (" << why << ")";
}

}  // namespace
