#pragma once
// The generator functions behind scenes_gen::generate(), one file each; the table of names is
// in generators.cpp.

#include "generators.h"

namespace scenes_gen {

tracer::Scene make_refraction(const GenOptions& options);
tracer::Scene make_spheres8000(const GenOptions& options);
tracer::Scene make_five(const GenOptions& options);
tracer::Scene make_random(const GenOptions& options);
tracer::Scene make_grid(const GenOptions& options);         // grid.h
tracer::Scene make_sphereflake(const GenOptions& options);  // sphereflake.h
tracer::Scene make_ring(const GenOptions& options);         // photon_scenes.cpp
tracer::Scene make_glass_caustic(const GenOptions& options);
tracer::Scene make_cornell(const GenOptions& options);
tracer::Scene make_furnace(const GenOptions& options);
tracer::Scene make_mesh(const GenOptions& options);  // mesh_scenes.cpp
tracer::Scene make_mesh_grid(const GenOptions& options);
tracer::Scene make_tessellated_spheres(const GenOptions& options);
tracer::Scene make_mesh_caustic(const GenOptions& options);  // photon_scenes.cpp

}  // namespace scenes_gen
