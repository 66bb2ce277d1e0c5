#pragma once
// "Model only what a scene requires": which photon maps a scene can use, decided from its lights
// and the materials its primitives use, before any photon is traced.
//
// - The caustic map holds light that reached a diffuse surface through specular bounces only
//   (LS+D): it needs a light, a specular surface (mirror, dielectric, or NFF with ks or T > 0)
//   and a diffuse surface that reflects (albedo > 0; a black surface shows no caustic).
// - The global map holds light after at least one diffuse bounce (L{S|D}*D minus the first
//   diffuse hit, which direct light covers): it needs a light and a diffuse surface that
//   reflects, for the bounce.
// Geometry can still keep the light away (a light inside a closed mirror); the photon tracer
// then stops the pass when its first round reaches no diffuse surface (photon_tracer.h).

#include "tracer/scene.h"

#include "accel/geometry.h"

#include <string>

namespace photon {

/// Which maps a scene can use, and why not when it cannot.
struct MapNeeds {
  bool caustic = false;        ///< A caustic map can hold light.
  bool global = false;         ///< A global map can hold light.
  std::string caustic_reason;  ///< Why not, when !caustic ("no specular surface").
  std::string global_reason;   ///< Why not, when !global.
};

MapNeeds map_needs(const tracer::Scene& scene);

/// A material's part in photon transport.
struct MaterialRole {
  bool specular = false;  ///< Reflects or refracts specularly (mirror, dielectric, NFF ks or T).
  bool diffuse = false;   ///< Has a diffuse part a photon can be stored on.
  bool reflects = false;  ///< That diffuse part reflects (albedo > 0).
};

MaterialRole role_of(const tracer::Material& m);

/// The box around every bounded primitive with a specular material; `all` is set when an
/// unbounded plane is specular (then every direction may lead to one). Empty when none.
struct SpecularBounds {
  accel::Aabb box;   ///< Box around the bounded specular primitives.
  bool all = false;  ///< A specular plane exists.
};

SpecularBounds specular_bounds(const tracer::Scene& scene);

}  // namespace photon
