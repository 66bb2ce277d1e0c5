#pragma once
// The knobs of the photon-mapping integrator: one struct, each default written once, here. They
// are read from the scene's "integrator" object and from `render --param NAME=VALUE`, swept by
// sweep files ("integrator_knobs"), and written back complete into every results row.

#include "density.h"
#include "knn.h"
#include "photon_tree_params.h"

#include "tracer/triangle_test.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>

namespace photon {

struct PhotonParams {
  /// Photons stored in the global map (light after at least one diffuse bounce), photons.
  int global_photons = 100000;
  /// Photons stored in the caustic map (light after specular bounces only), photons.
  int caustic_photons = 50000;
  /// Photons gathered per radiance estimate: the k of the kNN gather.
  int k = 50;
  /// Largest gather radius, world units; unset ("auto") = 1/20 of the diagonal of the box
  /// around the scene's bounded primitives (unbounded when there are none).
  std::optional<float> max_radius;
  /// Density-estimation kernel: box, cone (the paper's) or biweight.
  DensityFilter filter = DensityFilter::Cone;
  /// Cone filter constant: weight 1 - d / (cone_k r).
  float cone_k = 1.1f;
  /// Surface interactions per photon path before it is dropped.
  int max_photon_depth = 64;
  /// Final-gather rays per diffuse camera-path hit; 0 = read the global map
  /// directly there instead.
  int final_gather_rays = 0;
  /// Photon kd-tree variant: balanced (the paper's), sliding_midpoint, median_buckets or
  /// brute_force (photon/photon_tree_params.h); the image is bit-identical across them.
  PhotonTreeKind photon_tree = PhotonTreeKind::Balanced;
  /// Photons per leaf of the bucket trees (sliding_midpoint, median_buckets);
  /// the kd-tree's own default.
  int leaf_size = PhotonTreeParams{}.leaf_size;
  /// The paper's optimisation 2: reject photons from behind the surface before the heap.
  bool cull = true;
  /// The paper's optimisation 3: compute each photon's squared distance once (never changes the
  /// image).
  bool cache_distances = true;
  /// Seed of every random number of the photon paths and the final gather.
  std::uint64_t seed = 1;
  /// Trace only the maps the scene can use (no specular surface: no caustic map; no diffuse
  /// surface that reflects: no global map). false traces both, a caustic pass with nothing to
  /// aim at then emitting everywhere: what a tracer that does not check would spend.
  bool skip_unneeded_maps = true;
  /// Ray/triangle routine of camera, shadow and photon rays.
  tracer::TriangleTest triangle = tracer::TriangleTest::Watertight;

  /// The gather knobs of a map lookup, with the radius resolved to `radius` (world units).
  GatherParams gather(float radius) const;
  /// The density-estimation knobs.
  DensityParams density() const;
  /// The photon-tree knobs.
  PhotonTreeParams tree() const;

  /// The table (JSON in and out, max_radius as "auto" or its number; one-line errors such as
  /// "photon: knob 'k' must be in [1, 1048576], got 0"; the fronts of the accuracy knobs).
  static const knobs::KnobTable<PhotonParams>& knobs();
};

}  // namespace photon
