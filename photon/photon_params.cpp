#include "photon_params.h"

#include <limits>
#include <string>

namespace photon {

namespace {

constexpr int kMaxPhotons = std::numeric_limits<int>::max();  ///< 2^31 - 1: PhotonMap's limit.
constexpr int kMaxK = 1 << 20;

}  // namespace

GatherParams PhotonParams::gather(float radius) const {
  GatherParams g;
  g.k = k;
  g.max_radius = radius;
  g.cull = cull;
  g.cache_distances = cache_distances;
  return g;
}

DensityParams PhotonParams::density() const {
  DensityParams d;
  d.filter = filter;
  d.cone_k = cone_k;
  return d;
}

PhotonTreeParams PhotonParams::tree() const {
  PhotonTreeParams t;
  t.photon_tree = photon_tree;
  t.leaf_size = leaf_size;
  return t;
}

const knobs::KnobTable<PhotonParams>& PhotonParams::knobs() {
  using K = knobs::Knob<PhotonParams>;
  // Every accuracy knob here shares one front reference that has none of them: progressive
  // photon mapping run long at its own reference knobs (Integrator::reference_for_others), two
  // halves with independent seeds, its noise estimated from the halves and its remaining bias
  // from a render with 1/8 of its passes. Its camera paths are the photon integrator's
  // (Whitted's), so it converges to what the photon integrator estimates.
  const auto ppm_front = [](const char* values) { return knobs::Front{values, "ppm", "", "", true}; };
  static const knobs::KnobTable<PhotonParams> table(
      "photon",
      {K::integer("global_photons", &PhotonParams::global_photons, 1, kMaxPhotons, "photons",
                  "Photons in the global map (indirect light): more is less noise, less blur, slower.")
           .front(ppm_front("[1000, 3000, 10000, 30000, 100000, 300000, 1000000]")),
       K::integer("caustic_photons", &PhotonParams::caustic_photons, 1, kMaxPhotons, "photons",
                  "Photons in the caustic map (light focused by mirrors and glass): more is sharper.")
           .front(ppm_front("[1000, 3000, 10000, 30000, 100000, 300000, 1000000]")),
       K::integer("k", &PhotonParams::k, 1, kMaxK, "photons",
                  "Photons per density estimate (the k of the kNN gather): more is less noise and more blur.")
           .front(ppm_front("[1, 2, 5, 10, 20, 50, 100, 200, 500]")),
       K::number_or_auto("max_radius", &PhotonParams::max_radius, 0.0, 3.0e38, "world units",
                         "Largest gather radius: smaller cuts sparse estimates short (darker, faster); "
                         "auto = 1/20 of the diagonal of the scene's bounded primitives.")
           .open_below()
           .front(ppm_front("[0.01, 0.03, 0.1, 0.3, 1, 3]")),
       K::choice("filter", &PhotonParams::filter, density_filter_choices(),
                 "Density-estimation kernel: box, the paper's cone, or biweight.")
           .variant(),
       K::number("cone_k", &PhotonParams::cone_k, 1.0, 1e6, "",
                 "Cone filter constant (filter cone): lower weights near photons more, sharper edges.")
           .front(ppm_front("[1, 1.1, 1.5, 2, 3, 5, 10]")),
       K::integer("max_photon_depth", &PhotonParams::max_photon_depth, 1, 1000, "bounces",
                  "Surface interactions per photon path before it is dropped."),
       K::integer("final_gather_rays", &PhotonParams::final_gather_rays, 0, 65536, "rays",
                  "Final-gather rays per diffuse hit (0: read the global map directly).")
           .front(ppm_front("[0, 1, 4, 16, 64, 256]")),
       K::choice("photon_tree", &PhotonParams::photon_tree, photon_tree_choices(),
                 "Photon kd-tree variant; the image is bit-identical across them.")
           .variant(),
       K::integer("leaf_size", &PhotonParams::leaf_size, 1, 256, "photons",
                  "Photons per leaf of the bucket trees (sliding_midpoint, median_buckets)."),
       K::boolean("cull", &PhotonParams::cull,
                  "The paper's optimisation 2: reject photons from behind the surface before the heap."),
       K::boolean("cache_distances", &PhotonParams::cache_distances,
                  "The paper's optimisation 3: compute each photon's squared distance once (never changes the image)."),
       K::integer(knobs::kSeedKnob, &PhotonParams::seed, 0, ~0ull, "",
                  "Seed of every random number of the photon paths and the final gather."),
       K::boolean("skip_unneeded_maps", &PhotonParams::skip_unneeded_maps,
                  "Trace only the maps the scene can use (no specular surface: no caustic map; no "
                  "diffuse surface that reflects: no global map)."),
       tracer::triangle_knob(&PhotonParams::triangle)});
  return table;
}

}  // namespace photon
