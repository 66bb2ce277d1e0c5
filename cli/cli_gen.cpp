// `accelbench gen`: write a procedurally generated scene as JSON.

#include "cli/cli_util.h"
#include "cli/commands.h"

#include "scenes_gen/generators.h"
#include "input/file_read.h"
#include "tracer/scene_io.h"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

namespace cli {


namespace {

/// Largest --count gen writes: a million spheres is about 120 MB of JSON, within the scene-file
/// limit (input::kMaxSceneFileBytes) with room to spare.
constexpr int kMaxGenCount = 1'000'000;

struct GenFlags {
  std::string name;
  std::string out;
  std::string resolution;
  std::string seed = "1";
  std::string model;
  int count = 0;
  int samples_per_pixel = 1;
  bool list = false;
  CLI::Option* count_opt = nullptr;
  CLI::Option* spp_opt = nullptr;
};

int run_gen(const GenFlags& f) {
  if (f.list) {
    for (const std::string& name : scenes_gen::generator_names())
      std::printf("%-12s %s\n", name.c_str(), scenes_gen::generator_description(name).c_str());
    return 0;
  }
  if (f.name.empty()) throw std::runtime_error("gen: give a generator NAME (see gen --list)");
  if (f.out.empty()) throw std::runtime_error("gen: -o SCENE.json is required");
  if (std::filesystem::path(f.out).extension() != ".json")
    throw std::runtime_error("-o: expected a .json file name, got '" + f.out + "'");
  scenes_gen::GenOptions options;
  options.seed = parse_seed(f.seed, "--seed");
  if (f.count_opt->count()) options.count = f.count;
  options.model = f.model;
  int width = 0, height = 0;
  if (!f.resolution.empty()) parse_image_size(f.resolution, "--resolution", width, height);
  tracer::Scene scene = scenes_gen::generate(f.name, options);
  // A scene file larger than the loader's limit could never be read back. Mesh files are written
  // as references, so only the primitives written one by one count.
  std::uint64_t inline_primitives = scene.geometry.bounded_count();
  for (const tracer::MeshInstance& m : scene.meshes) inline_primitives -= m.triangle_count;
  if (inline_primitives > std::uint64_t(kMaxGenCount))
    throw std::runtime_error("--count: gen writes scenes of at most " + std::to_string(kMaxGenCount) +
                             " primitives written one by one (a larger file would pass the scene-file limit of " +
                             input::byte_text(input::kMaxSceneFileBytes) + "); " + f.name + " made " +
                             std::to_string(inline_primitives) + " (sweeps take the generator itself)");
  if (width) scene.camera.width = width, scene.camera.height = height;

  if (f.spp_opt->count()) scene.camera.samples_per_pixel = f.samples_per_pixel;
  tracer::save_scene_file(scene, f.out);
  std::printf("wrote %s: %s\n", f.out.c_str(), describe_scene(scene).c_str());
  return 0;
}

}  // namespace

void add_gen_command(CLI::App& app, int& exit_code) {
  auto flags = std::make_shared<GenFlags>();
  std::string names;
  for (const std::string& n : scenes_gen::generator_names())
    names += (names.empty() ? "" : ", ") + n;
  CLI::App* cmd = app.add_subcommand("gen", "Generate a scene file; generators: " + names);
  cmd->add_option("NAME", flags->name, "Generator name (see --list)");
  cmd->add_option("-o,--output", flags->out, "Scene JSON to write");
  cmd->add_option("--seed", flags->seed, "Random seed, an integer in [0, 2^64-1] (same seed, same scene)");
  flags->count_opt =
      cmd->add_option("--count", flags->count, "Number of primitives, for generators that take one")
          ->check(CLI::NonNegativeNumber);
  cmd->add_option("--model", flags->model,
                  "Model of the mesh generators: bunny, ogre, nefertiti, beast, igea, teapot, spot, fandisk, or a "
                  "model file");
  cmd->add_option("--resolution", flags->resolution, "Image size WIDTHxHEIGHT stored in the scene");
  flags->spp_opt =
      cmd->add_option("--spp", flags->samples_per_pixel, "Samples per pixel stored in the scene")
          ->check(CLI::Range(1, 65536));
  cmd->add_flag("--list", flags->list, "List the generators and exit");
  cmd->callback([flags, &exit_code] { exit_code = run_gen(*flags); });
}

}  // namespace cli
