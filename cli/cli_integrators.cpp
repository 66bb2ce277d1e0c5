// `accelbench integrators`: the integrator table (integrators/integrators.h) and every integrator's
// knobs, read from its knob table. --markdown prints the knob reference of docs/tracer.md,
// --json the table as data; the tests check that the docs are up to date.

#include "cli/commands.h"
#include "integrators/integrators.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

namespace cli {

namespace {

struct IntegratorsFlags {
  bool json = false;
  bool markdown = false;
};

int run(const IntegratorsFlags& f) {
  if (f.json && f.markdown) throw std::runtime_error("--json and --markdown: give one of them");
  if (f.json) {
    std::printf("%s\n", integrators::table_json().dump(2).c_str());
    return 0;
  }
  if (f.markdown) {
    std::printf("%s", integrators::markdown().c_str());
    return 0;
  }
  for (const tracer::Integrator* i : integrators::all()) {
    std::string knobs;
    for (const std::string& k : i->knob_table().names()) knobs += (knobs.empty() ? "" : ", ") + k;
    std::printf("%-8s %s\n         knobs: %s\n", std::string(i->name).c_str(), std::string(i->description).c_str(),
                knobs.empty() ? "none" : knobs.c_str());
  }
  return 0;
}

}  // namespace

void add_integrators_command(CLI::App& app, int& exit_code) {
  auto flags = std::make_shared<IntegratorsFlags>();
  CLI::App* cmd = app.add_subcommand("integrators", "List the integrators and their knobs");
  cmd->add_flag("--json", flags->json, "The integrator table as JSON");
  cmd->add_flag("--markdown", flags->markdown, "The integrators' knob reference as Markdown (docs/tracer.md)");
  cmd->callback([flags, &exit_code] { exit_code = run(*flags); });
}

}  // namespace cli
