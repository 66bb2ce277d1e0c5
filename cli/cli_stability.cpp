// `accelbench stability`: a scene and its variants at the extremes through naive in float and in
// double and through every structure; a table on stdout, progress on stderr, JSON with --out.
// Any structure that disagrees with naive, or any image with a NaN or infinity, is a failure and
// makes the exit status 1.

#include "cli/cli_util.h"
#include "cli/commands.h"
#include "integrators/integrators.h"
#include "harness/stability.h"

#include "tracer/scene_io.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

namespace cli {

using namespace harness;  // the command line drives the harness


namespace {

struct StabilityFlags {
  std::string scene;
  std::string accel;
  std::string resolution = "96x72";
  std::string variants = "all";
  std::string integrator;
  bool spd = false;
  bool no_reference = false;
  int threads = 0;
  std::string out;
  std::string images;
  std::vector<std::string> params;  ///< --param NAME=VALUE: the integrator's knobs.
};

int run(const StabilityFlags& f) {
  if (!f.out.empty() && std::filesystem::path(f.out).extension() != ".json")
    throw std::runtime_error("--out: expected a .json file name, got '" + f.out + "'");
  if (f.spd && !f.integrator.empty() && f.integrator != "spd")
    throw std::runtime_error("--spd: is --integrator spd, but --integrator " + f.integrator +
                             " was given too");
  StabilityOptions o;
  o.scene_label = f.scene;
  o.integrator = &integrators::named(f.spd ? "spd" : f.integrator.empty() ? "whitted" : f.integrator,
                                   "--integrator");
  o.integrator_params = integrators::parse_knob_items(f.params, "--param");
  if (o.integrator_params.contains(tracer::kPrecisionKnob))
    throw std::runtime_error("--param: the suite renders naive in float and in double itself; leave out 'precision'");
  // Checks the knobs, and that the integrator has `precision` (one that lacks it fails here).
  nlohmann::json checked = o.integrator_params;
  checked[tracer::kPrecisionKnob] = tracer::precision_name(tracer::Precision::Double);
  o.integrator->params(checked);
  parse_image_size(f.resolution, "--resolution", o.width, o.height);
  o.structures = parse_checked_structures(f.accel.empty() ? default_structures() : f.accel, "--accel");
  o.variants = select_variants(f.variants, "--variants");
  o.threads = f.threads;
  o.reference = !f.no_reference;
  o.images_dir = f.images;
  const tracer::Scene scene = tracer::load_scene_file(f.scene);

  std::cerr << "stability " << f.scene << ": " << describe_scene(scene) << "; " << o.variants.size()
            << " variants at " << o.width << "x" << o.height << ", integrator "
            << o.integrator->name << (o.integrator_params.empty() ? "" : " " + o.integrator_params.dump())
            << ", naive in float" << (o.reference ? " and double" : "")
            << " and " << o.structures.size() << " structures\n";
  const nlohmann::json doc = run_stability(scene, o, std::cerr);
  std::cout << stability_table(doc);
  const int failures = doc["failures"].get<int>();
  std::cout << (failures == 0 ? "every structure equals naive on every variant; no NaN or infinity\n"
                              : std::to_string(failures) + " failure(s): see the FAILED lines above\n");
  if (!f.out.empty()) {
    const std::filesystem::path dir = std::filesystem::path(f.out).parent_path();
    if (!dir.empty()) std::filesystem::create_directories(dir);
    std::ofstream out(f.out);
    out << doc.dump(1) << '\n';
    if (!out) throw std::runtime_error("--out: cannot write '" + f.out + "'");
    std::cout << "wrote " << f.out << "\n";
  }
  return failures == 0 ? 0 : 1;
}

}  // namespace

void add_stability_command(CLI::App& app, int& exit_code) {
  auto flags = std::make_shared<StabilityFlags>();
  CLI::App* cmd = app.add_subcommand(
      "stability",
      "Render a scene moved and scaled to the extremes (and more variants) through naive in float "
      "and double and through every structure; compare");
  cmd->add_option("SCENE", flags->scene, "Scene file (.json or .nff)")->required();
  cmd->add_option("--accel", flags->accel,
                  "Structures checked against naive, comma-separated NAME or NAME:KNOB=VALUE "
                  "(default: " + default_structures() + ")");
  cmd->add_option("--resolution", flags->resolution, "Image size WIDTHxHEIGHT (default 96x72)");
  cmd->add_option("--variants", flags->variants,
                  "Comma-separated variant groups or names: base, translate_x, translate_diag, "
                  "scale, camera, snapped, duplicated, touching, a name such as scale_1e-4, all "
                  "(default) or quick");
  cmd->add_option("--integrator", flags->integrator,
                  "Integrator (default whitted); one of " + integrators::names());
  cmd->add_flag("--spd", flags->spd, "Shorthand for --integrator spd (SPD test rules)");
  cmd->add_flag("--no-reference", flags->no_reference,
                "Skip the double-precision renders (the reference)");
  cmd->add_option("--threads", flags->threads, "Render threads; 0 = all cores")
      ->check(CLI::Range(0, 4096));
  cmd->add_option("-o,--out", flags->out, "Results JSON to write (results/schema/stability.schema.json)");
  cmd->add_option("--param", flags->params,
                  "An integrator knob for every render, NAME=VALUE (repeatable), e.g. --param triangle=moller");
  cmd->add_option("--images", flags->images, "Directory for a PNG of every render (float, double)");
  cmd->callback([flags, &exit_code] { exit_code = run(*flags); });
}

}  // namespace cli
