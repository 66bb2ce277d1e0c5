#include "bench_scenes.h"

#include <algorithm>
#include <tuple>

namespace bench {

const std::vector<std::string> kMeshScenes = {"bunny", "ogre", "nefertiti", "grid1M"};
const std::string kBuildOnlyMeshScene = "grid10M";
const std::vector<std::pair<std::string, std::uint64_t>> kSpotGrids = {
    {"spots_6e3", 5'856}, {"spots_1e4", 10'000}, {"spots_1e5", 100'000}, {"spots_1e6", 1'000'000},
    {"spots_1e7", 10'000'000}};
const std::vector<std::pair<std::string, std::uint64_t>> kTessellated = {
    {"tess_L0", 0}, {"tess_L1", 1}, {"tess_L2", 2}, {"tess_L3", 3}};

std::optional<std::pair<std::string, scenes_gen::GenOptions>> scaling_scene(const std::string& name) {
  for (const auto& [label, count] : kSpotGrids)
    if (label == name) {
      scenes_gen::GenOptions gen;
      gen.model = "spot";
      gen.count = count;
      return std::pair{std::string("mesh_grid"), gen};
    }
  for (const auto& [label, level] : kTessellated)
    if (label == name) {
      scenes_gen::GenOptions gen;
      gen.count = level;
      return std::pair{std::string("tessellated_spheres"), gen};
    }
  return std::nullopt;
}

bool is_mesh_scene(const std::string& name) {
  return name == kBuildOnlyMeshScene || scaling_scene(name) ||
         std::find(kMeshScenes.begin(), kMeshScenes.end(), name) != kMeshScenes.end();
}

tracer::Scene bench_scene(const std::string& name) {
  scenes_gen::GenOptions gen;
  std::string generator = name;
  if (name == "random1M") {
    generator = "random";
    gen.count = 1'000'000;
  } else if (name == "grid1M" || name == kBuildOnlyMeshScene) {
    generator = "mesh_grid";
    gen.count = name == "grid1M" ? 1'000'000 : 10'000'000;
  } else if (const auto scaling = scaling_scene(name)) {
    std::tie(generator, gen) = *scaling;
  } else if (is_mesh_scene(name)) {
    generator = "mesh";
    gen.model = name;
  }
  return scenes_gen::generate(generator, gen);
}

}  // namespace bench
