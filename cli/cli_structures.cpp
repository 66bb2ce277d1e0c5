// `accelbench structures`: the structure registry, read from the one table in accel/registry.h:
// names, what each is, whether this build has it, and every knob (type, default, range, unit,
// doc). --markdown prints the knob reference of docs/structures.md, --json the registry file
// scripts/plot.py reads (scripts/structures.json); the tests check both are up to date.

#include "cli/commands.h"

#include "accel/accel.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

namespace cli {

namespace {

struct StructuresFlags {
  bool json = false;
  bool markdown = false;
};

int run(const StructuresFlags& f) {
  if (f.json && f.markdown) throw std::runtime_error("--json and --markdown: give one of them");
  if (f.json) {
    std::printf("%s\n", accel::registry_json().dump(2).c_str());
    return 0;
  }
  if (f.markdown) {
    std::printf("%s", accel::knob_reference_markdown().c_str());
    return 0;
  }
  for (const accel::StructureInfo& s : accel::structures()) {
    std::string knobs;
    for (const std::string& k : s.knobs) {
      if (!knobs.empty()) knobs += ", ";
      knobs += k;
    }
    const std::string missing = s.built ? "" : " [" + s.missing + "]";
    std::printf("%-8s %s%s\n         knobs: %s\n", s.name.c_str(), s.summary.c_str(), missing.c_str(),
                knobs.empty() ? "none" : knobs.c_str());
  }
  return 0;
}

}  // namespace

void add_structures_command(CLI::App& app, int& exit_code) {
  auto flags = std::make_shared<StructuresFlags>();
  CLI::App* cmd = app.add_subcommand("structures", "List the registered structures and their knobs");
  cmd->add_flag("--json", flags->json, "The registry as JSON (scripts/structures.json)");
  cmd->add_flag("--markdown", flags->markdown, "The knob reference as Markdown (docs/structures.md)");
  cmd->callback([flags, &exit_code] { exit_code = run(*flags); });
}

}  // namespace cli
