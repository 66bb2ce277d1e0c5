#pragma once
// A scene: camera, background, lights, materials, geometry and render settings.
// Defaults are written here once; docs/scene-format.md documents them for the JSON format.

#include "mesh_instance.h"
#include "scene_geometry.h"

#include "knobs/knob_table.h"

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace tracer {

using Color = glm::vec3;

struct Camera {
  Vec3 position{0.0f, 0.0f, 5.0f};  ///< Eye point, world units.
  Vec3 look_at{0.0f};               ///< Point the view is centred on, world units.
  Vec3 up{0.0f, 1.0f, 0.0f};        ///< Up direction; need not be perpendicular to the view.
  float vfov_deg = 45.0f;           ///< Vertical field of view, degrees, in (0, 180).
  int width = 640;                  ///< Image width, pixels.
  int height = 480;                 ///< Image height, pixels.
  int samples_per_pixel = 1;        ///< Samples per pixel (deterministic stratified jitter when > 1).
  bool left_handed = false;         ///< World is left-handed (NFF/SPD): image right = up x view.
  float hither = 0.0f;              ///< Near clip distance along the view direction, world units (NFF).
};

struct PointLight {
  Vec3 position{0.0f, 10.0f, 0.0f};  ///< World units.
  float power_w = 1000.0f;           ///< Radiant power, watts, emitted uniformly in all directions.
  Color color{1.0f};                 ///< Spectral tint multiplying the power.
};

/// Nff: the classic NFF/SPD surface (albedo as colour, kd, ks, shininess, transmittance, ior),
/// shaded by tracer/nff_shading.h.
enum class MaterialType : std::uint8_t { Diffuse, Mirror, Dielectric, Nff };

struct Material {
  std::string name;                    ///< Unique name the primitives refer to.
  MaterialType type = MaterialType::Diffuse;
  Color albedo{0.8f};                  ///< Diffuse: Lambertian reflectance in [0, 1].
  float specular = 0.0f;               ///< Diffuse: Phong highlight weight in [0, 1]; 0 = none.
  float shininess = 32.0f;             ///< Diffuse: Phong exponent (> 0).
  Color reflectance{1.0f};             ///< Mirror: reflectance per channel in [0, 1].
  float ior = 1.5f;                    ///< Dielectric: index of refraction (> 0).
  Color absorption{0.0f};              ///< Dielectric: Beer–Lambert absorption per world unit.
  float kd = 1.0f;                     ///< Nff: diffuse coefficient multiplying albedo, >= 0.
  float ks = 0.0f;                     ///< Nff: reflection coefficient, also the highlight weight, >= 0.
  float transmittance = 0.0f;          ///< Nff: weight of the refracted ray (NFF T), >= 0; ior used when > 0.
};

/// The scene file's "render" object: the recursion limits a render without knobs uses.
struct RenderSettings {
  int max_depth = 8;            ///< Maximum recursion depth; the camera ray is depth 1.
  float min_weight = 1e-3f;     ///< Rays whose path weight falls below this are not traced.

  /// Name, range, unit and doc line of both: the scene file's reader and writer and the docs.
  static const knobs::KnobTable<RenderSettings>& knobs();
};

/// The integrator a scene asks for, and its knobs. The tracer only stores them: the integrator
/// table (integrators/integrators.h) knows the names, and each integrator checks its own knobs.
struct IntegratorChoice {
  std::string name;                                  ///< Integrator name; "" = the command's default.
  nlohmann::json knobs = nlohmann::json::object();   ///< Its knobs as written in the scene.
};

struct Scene {
  Camera camera;
  Color background{0.0f};       ///< Radiance of rays that escape.
  std::vector<PointLight> lights;
  std::vector<Material> materials;
  Geometry geometry;
  /// The meshes read from model files; their triangles are in geometry.triangles.
  std::vector<MeshInstance> meshes;
  RenderSettings render;
  IntegratorChoice integrator;  ///< Scene JSON "integrator"; the command line overrides it.
};

}  // namespace tracer
