// The mesh generators: `mesh` (a standard model framed), `mesh_grid` (instanced copies of one,
// flattened into one triangle list) and `tessellated_spheres` (spheres8000 with every sphere an
// icosphere).

#include "mesh_scenes.h"

#include "closed_meshes.h"
#include "framing.h"
#include "generator_functions.h"
#include "materials.h"

#include "tracer/scene_error.h"
#include "tracer/scene_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string_view>

namespace scenes_gen {

namespace {

struct Model {
  std::string_view name;
  std::string_view file;
};

constexpr std::array kModels = {
    Model{"bunny", "stanford-bunny.obj"}, Model{"ogre", "ogre.obj"},       Model{"nefertiti", "nefertiti.obj"},
    Model{"beast", "beast.obj"},          Model{"igea", "igea.ply"},       Model{"teapot", "teapot.obj"},
    Model{"spot", "spot.obj"},            Model{"fandisk", "fandisk.obj"},
};

std::string meshes_dir() {
  if (const char* env = std::getenv("ACCELBENCH_MESHES_DIR"); env && *env) return env;
  return ACCELBENCH_MESHES_DIR;
}

accel::Aabb bounds_of(const tracer::MeshData& mesh) {
  accel::Aabb b;
  for (const auto& t : mesh.triangles)
    for (const std::uint32_t i : t) b.grow(mesh.vertices[i]);
  return b;
}

tracer::MeshData load_model(const std::string& path, std::uint64_t max_memory_bytes) {
  try {
    return tracer::load_mesh_file(path, max_memory_bytes);
  } catch (const tracer::SceneError& e) {
    throw GenError(e.what());
  }
}

/// Camera, lights, floor and materials around `bounds` (y up): material 0 is the model's.
void frame_on_floor(tracer::Scene& scene, const accel::Aabb& bounds) {
  scene.materials = {diffuse("model", {0.75f, 0.72f, 0.68f}, 0.2f), diffuse("floor", {0.55f, 0.55f, 0.6f})};
  const float size = std::max(glm::length(bounds.extent()), 1e-6f);
  tracer::Plane floor;
  floor.normal = {0.0f, 1.0f, 0.0f};
  floor.offset = bounds.lo.y;
  floor.material = 1;
  scene.geometry.planes.push_back(floor);
  scene.camera = frame_bounds(bounds, tracer::Vec3(0.6f, 0.45f, 1.0f));
  scene.camera.width = 640;
  scene.camera.height = 480;
  const tracer::Vec3 centre = bounds.center();
  scene.lights = {light_at(centre, {0.8f, 1.5f, 1.2f}, size, 60.0f), light_at(centre, {-1.2f, 0.8f, 0.6f}, size, 20.0f)};
  scene.background = {0.05f, 0.05f, 0.07f};
  scene.render.max_depth = 4;
}

int count_or(const GenOptions& options, int fallback) { return options.count ? *options.count : fallback; }

}  // namespace

std::vector<std::string> model_names() {
  std::vector<std::string> out;
  for (const Model& m : kModels) out.emplace_back(m.name);
  return out;
}

std::string model_path(const std::string& name_or_path) {
  for (const Model& m : kModels)
    if (m.name == name_or_path) {
      const std::filesystem::path p = std::filesystem::path(meshes_dir()) / m.file;
      if (!std::filesystem::exists(p))
        throw GenError("model '" + name_or_path + "': " + p.string() +
                       " not found (the shared meshes folder; set ACCELBENCH_MESHES_DIR)");
      return p.lexically_normal().string();
    }
  if (name_or_path.find('.') == std::string::npos) {
    std::string known;
    for (const Model& m : kModels) known += (known.empty() ? "" : ", ") + std::string(m.name);
    throw GenError("unknown model '" + name_or_path + "' (known: " + known + ", or a path to an .obj or .ply file)");
  }
  return name_or_path;
}

tracer::Scene scene_around_model(const std::string& path, std::uint64_t max_memory_bytes) {
  const tracer::MeshData mesh = load_model(path, max_memory_bytes);
  tracer::Scene scene;
  frame_on_floor(scene, bounds_of(mesh));
  tracer::MeshInstance instance;
  instance.path = std::filesystem::absolute(path).lexically_normal().string();
  instance.material = 0;
  tracer::add_mesh(scene, mesh, std::move(instance));
  return scene;
}

tracer::Scene make_mesh(const GenOptions& options) {
  return scene_around_model(model_path(options.model.empty() ? "bunny" : options.model));
}

tracer::Scene make_mesh_grid(const GenOptions& options) {
  const std::string path = model_path(options.model.empty() ? "bunny" : options.model);
  const tracer::MeshData mesh = load_model(path, 0);
  const std::uint64_t target = std::uint64_t(count_or(options, 1'000'000));
  const std::uint64_t copies = std::max<std::uint64_t>(1, (target + mesh.triangles.size() - 1) / mesh.triangles.size());
  const int side = int(std::ceil(std::cbrt(double(copies)) - 1e-9));
  const accel::Aabb box = bounds_of(mesh);
  const glm::dvec3 pitch = 1.2 * glm::dvec3(box.extent());
  tracer::Scene scene;
  accel::Aabb all;
  std::uint64_t placed = 0;
  for (int z = 0; z < side && placed < copies; ++z)
    for (int y = 0; y < side && placed < copies; ++y)
      for (int x = 0; x < side && placed < copies; ++x, ++placed) {
        tracer::MeshInstance instance;
        instance.path = std::filesystem::absolute(path).lexically_normal().string();
        instance.transform.translate = pitch * glm::dvec3(x, y, z);
        all.grow(instance.transform.apply(box.lo));
        all.grow(instance.transform.apply(box.hi));
        tracer::add_mesh(scene, mesh, std::move(instance));
      }
  frame_on_floor(scene, all);
  return scene;
}

tracer::Scene make_tessellated_spheres(const GenOptions& options) {
  const int level = count_or(options, 1);
  if (level > 3)
    throw GenError("tessellated_spheres: --count is the subdivision level, 0-3 (3: 10,240,000 triangles), got " +
                   std::to_string(level));
  // spheres8000 itself, then every sphere replaced by an icosphere of the same centre, radius and
  // material, shaded smooth: each vertex carries the sphere's own normal there (the unit
  // icosphere's vertex), as a tessellated model would.
  tracer::Scene scene = make_spheres8000(options);
  const tracer::MeshData unit = icosphere(level);
  std::vector<tracer::Sphere> spheres;
  spheres.swap(scene.geometry.spheres);
  tracer::Geometry& g = scene.geometry;
  g.triangles.reserve(spheres.size() * unit.triangles.size());
  g.vertex_normals.reserve(3 * spheres.size() * unit.triangles.size());
  std::vector<tracer::Vec3> placed(unit.vertices.size());
  for (const tracer::Sphere& s : spheres) {
    for (std::size_t i = 0; i < placed.size(); ++i) placed[i] = s.center + s.radius * unit.vertices[i];
    for (const auto& t : unit.triangles) {
      g.triangles.push_back({placed[t[0]], placed[t[1]], placed[t[2]], s.material, std::int32_t(g.vertex_normals.size())});
      for (const std::uint32_t v : t) g.vertex_normals.push_back(unit.vertices[v]);
    }
  }
  return scene;
}

}  // namespace scenes_gen
