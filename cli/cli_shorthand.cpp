#include "cli/cli_shorthand.h"

#include "integrators/integrators.h"

#include "accel/accel.h"
#include "knobs/knob_table.h"

#include <stdexcept>

namespace cli {


namespace {

void add_unique(std::vector<ShorthandFlag>& out, ShorthandFlag f) {
  for (const ShorthandFlag& have : out)
    if (have.flag == f.flag) return;
  out.push_back(std::move(f));
}

}  // namespace

std::vector<ShorthandFlag> structure_shorthand_flags() {
  std::vector<ShorthandFlag> out;
  for (const accel::StructureInfo& s : accel::structures())
    for (const nlohmann::json& k : s.knob_table)
      if (k.contains("flag"))
        add_unique(out, {k["flag"], k["name"],
                         // Ranges differ between structures (bvh leaves hold at most 255): the
                         // registry's knob reference has each one's.
                         "Structure knob " + k["name"].get<std::string>() + ": " + k["doc"].get<std::string>() +
                             " (see `accelbench structures`)",
                         k["type"] == "choice"});
  return out;
}

std::vector<ShorthandFlag> integrator_shorthand_flags() {
  std::vector<ShorthandFlag> out;
  for (const tracer::Integrator* integrator : integrators::all())
    for (const knobs::KnobInfo& k : integrator->knob_table().knob_infos())
      if (!k.flag.empty())
        add_unique(out, {k.flag, k.name, "Integrator knob " + k.name + " (" + k.range + "): " + k.doc,
                         k.type == knobs::KnobType::Choice});
  return out;
}

void add_shorthand_flags(CLI::App& cmd, const std::vector<ShorthandFlag>& flags, ShorthandValues& values,
                         bool list) {
  for (const ShorthandFlag& f : flags) {
    CLI::Option* o = cmd.add_option(f.flag, values[f.knob], list ? f.help + "; comma-separated values" : f.help);
    if (list) o->delimiter(',');
    else o->expected(1);
  }
}

nlohmann::json shorthand_knobs(const ShorthandValues& values, const nlohmann::json& taken) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [knob, texts] : values) {
    if (texts.empty()) continue;
    if (taken.contains(knob)) throw std::runtime_error("--knob: '" + knob + "' is given twice");
    out[knob] = knobs::knob_value_from_text(texts.back());
  }
  return out;
}

}  // namespace cli
