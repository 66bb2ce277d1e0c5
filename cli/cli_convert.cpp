// `accelbench convert`: read a scene in any supported format (NFF included) and write it as JSON.

#include "cli/cli_util.h"
#include "cli/commands.h"

#include "scenes_gen/generators.h"
#include "scenes_gen/mesh_scenes.h"
#include "tracer/mesh_file.h"
#include "tracer/scene_io.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

namespace cli {


namespace {

bool is_model_file(const std::string& path) {
  try {
    tracer::mesh_format_of(path);
    return true;
  } catch (const tracer::SceneError&) {
    return false;
  }
}

struct ConvertFlags {
  std::string input;
  std::string output;
};

int run_convert(const ConvertFlags& f) {
  if (std::filesystem::path(f.output).extension() != ".json")
    throw std::runtime_error("-o: expected a .json file name, got '" + f.output + "'");
  // A model file becomes a scene around it; a scene file is converted as it is.
  const bool model = is_model_file(f.input);
  const tracer::Scene scene =
      model ? scenes_gen::scene_around_model(f.input) : tracer::load_scene_file(f.input);
  tracer::save_scene_file(scene, f.output);
  std::printf("wrote %s: %s\n", f.output.c_str(), describe_scene(scene).c_str());
  return 0;
}

}  // namespace

void add_convert_command(CLI::App& app, int& exit_code) {
  auto flags = std::make_shared<ConvertFlags>();
  CLI::App* cmd = app.add_subcommand(
      "convert", "Convert a scene (.nff or .json) to our JSON format, or write a scene around a model "
                 "(.obj, .ply, .gltf, ...): framed camera, lights and a floor; the scene refers to the model file");
  cmd->add_option("SCENE", flags->input, "Scene file (.nff, .json) or model file (.obj, .ply, .gltf, ...) to read")
      ->required();
  cmd->add_option("-o,--output", flags->output, "JSON scene file to write")->required();
  cmd->callback([flags, &exit_code] { exit_code = run_convert(*flags); });
}

}  // namespace cli
