#pragma once
// The shorthand flags of the commands that take knobs (`--max-depth 8` beside
// `--knob max_depth=8`), derived from the knob tables: a knob marked Knob::shorthand() in any
// structure's or integrator's table gets its flag on render, sweep and tune, with the table's
// doc line as its help. No command spells a knob's flag itself.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

namespace cli {


/// One shorthand flag and the knob it sets.
struct ShorthandFlag {
  std::string flag;        ///< "--max-depth".
  std::string knob;        ///< "max_depth".
  std::string help;        ///< "Structure knob max_depth: <doc>".
  bool choice = false;     ///< The knob picks one of a list of spellings (placement, split).
};

/// The structures' shorthand flags, one per flag, in registry order.
std::vector<ShorthandFlag> structure_shorthand_flags();

/// The integrators' shorthand flags, one per flag, in table order.
std::vector<ShorthandFlag> integrator_shorthand_flags();

/// The text each shorthand flag was given, by knob name.
using ShorthandValues = std::map<std::string, std::vector<std::string>>;

/// Registers `flags` on `cmd`; what each is given lands in values[knob]. With `list`, a flag
/// takes comma-separated values (sweeps), else one value.
void add_shorthand_flags(CLI::App& cmd, const std::vector<ShorthandFlag>& flags, ShorthandValues& values,
                         bool list);

/// The knobs the shorthand flags set, as JSON values (numbers and booleans where they read as
/// one; the knob tables check them), one value per flag given once. Throws std::runtime_error
/// when a knob is also in `taken` (given twice, e.g. by --knob too).
nlohmann::json shorthand_knobs(const ShorthandValues& values, const nlohmann::json& taken = nlohmann::json::object());

}  // namespace cli
