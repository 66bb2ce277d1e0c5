#pragma once
// The sphereflake of Eric Haines' Standard Procedural Databases ("balls"): a sphere with nine
// spheres of a third its radius on its surface, recursively. Size factor n has
// (9^(n+1) - 1) / 8 spheres: 10, 91, 820, 7381 (n = 4, the SPD default), 66430.

#include "generators.h"

#include "tracer/scene.h"

namespace scenes_gen {

/// Smallest and largest accepted size factor.
inline constexpr int kSphereflakeMinSize = 0;
inline constexpr int kSphereflakeMaxSize = 6;

/// Spheres in a sphereflake of size factor `size`.
long long sphereflake_sphere_count(int size);

/// Default size factor: SPD's own, 7381 spheres.
inline constexpr int kSphereflakeDefaultSize = 4;

/// The sphereflake of size factor options.count (default 4) in [0, 6]; throws GenError outside.
/// Deterministic: it has no randomness, so the seed is unused.
tracer::Scene make_sphereflake(const GenOptions& options);

}  // namespace scenes_gen
