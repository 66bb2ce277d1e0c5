#include "generators.h"

#include "generator_functions.h"

#include <array>

namespace scenes_gen {

namespace {

struct Entry {
  std::string_view name;
  std::string_view description;
  bool takes_count;  ///< Whether --count means something to this generator.
  tracer::Scene (*make)(const GenOptions&);
  bool takes_model = false;  ///< Whether --model means something to this generator.
};

constexpr std::array kGenerators = {
    Entry{"refraction", "the paper's Fig. 1: a glass bar before a checkered wall", false, make_refraction},
    Entry{"spheres8000", "the paper's Fig. 7: 20x20x20 jittered spheres in a 10-unit cube (seeded)", false,
          make_spheres8000},
    Entry{"five", "the paper's Fig. 8: five spheres (glass, mirror, diffuse)", false, make_five},
    Entry{"random", "--count N uniform random spheres in a 10-unit cube (seeded; default N 1000)", true,
          make_random},
    Entry{"grid", "--count N spheres on a regular cubic lattice (default N 1000)", true, make_grid},
    Entry{"ring", "the paper's Fig. 4: a mirror ring on a floor, lit from the side (photon mapping: cardioid caustic)",
          false, make_ring},
    Entry{"glass_caustic", "the paper's Fig. 5: a glass sphere focusing a point light on a floor (photon mapping)",
          false, make_glass_caustic},
    Entry{"cornell", "a Cornell box with a mirror and a glass sphere (photon mapping: colour bleeding, caustics)",
          false, make_cornell},
    Entry{"furnace", "a point light at the centre of a closed diffuse sphere, seen from inside (analytic radiance)",
          false, make_furnace},
    Entry{"sphereflake", "SPD 'balls' sphereflake; --count is its size factor 0-6 (default 4: 7381 spheres)", true,
          make_sphereflake},
    Entry{"mesh", "--model NAME: a standard model (bunny, ogre, nefertiti, beast, igea, teapot, spot, fandisk) or a "
          "model file, framed on a floor", false, make_mesh, true},
    Entry{"mesh_grid", "--count N triangles (default 1000000) of instanced copies of --model (default bunny), "
          "flattened", true, make_mesh_grid, true},
    Entry{"mesh_caustic", "--model NAME (default bunny) in glass on a diffuse floor under a point light: its caustic "
          "(photon mapping)", false, make_mesh_caustic, true},
    Entry{"tessellated_spheres", "spheres8000 with each sphere an icosphere; --count is its subdivision level 0-3 "
          "(default 1: 640,000 triangles)", true, make_tessellated_spheres},
};

const Entry* find(std::string_view name) {
  for (const Entry& e : kGenerators)
    if (e.name == name) return &e;
  return nullptr;
}

}  // namespace

tracer::Scene generate(std::string_view name, const GenOptions& options) {
  const Entry* e = find(name);
  if (!e) {
    std::string known;
    for (const Entry& g : kGenerators) known += (known.empty() ? "" : ", ") + std::string(g.name);
    throw GenError("unknown generator '" + std::string(name) + "' (known: " + known + ")");
  }
  if (options.count && !e->takes_count)
    throw GenError(std::string(name) + ": takes no count (it has a fixed size)");
  if (!options.model.empty() && !e->takes_model)
    throw GenError(std::string(name) + ": takes no model (only mesh and mesh_grid do)");
  if (options.count && (*options.count < 0 || *options.count > kMaxCount))
    throw GenError(std::string(name) + ": count must be in [0, " + std::to_string(kMaxCount) + "], got " +
                   std::to_string(*options.count));
  tracer::Scene scene = e->make(options);
  scene.geometry.finalize();
  return scene;
}

bool generator_takes_model(std::string_view name) {
  const Entry* e = find(name);
  return e && e->takes_model;
}

std::vector<std::string> generator_names() {
  std::vector<std::string> out;
  for (const Entry& e : kGenerators) out.emplace_back(e.name);
  return out;
}

std::string generator_description(std::string_view name) {
  const Entry* e = find(name);
  return e ? std::string(e->description) : std::string();
}

}  // namespace scenes_gen
