#include "photon_params.h"

#include "accel/params_json.h"

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

void to_json(nlohmann::json& j, const PhotonParams& p) {
  j = {{"global_photons", p.global_photons},
       {"caustic_photons", p.caustic_photons},
       {"k", p.k},
       {"max_radius", p.max_radius ? nlohmann::json(*p.max_radius) : nlohmann::json("auto")},
       {"filter", std::string(name_of(p.filter))},
       {"cone_k", p.cone_k},
       {"max_photon_depth", p.max_photon_depth},
       {"final_gather_rays", p.final_gather_rays},
       {"photon_tree", std::string(name_of(p.photon_tree))},
       {"leaf_size", p.leaf_size},
       {"cull", p.cull},
       {"cache_distances", p.cache_distances},
       {"seed", p.seed},
       {"skip_unneeded_maps", p.skip_unneeded_maps}};
}

void from_json(const nlohmann::json& j, PhotonParams& p) {
  accel::KnobReader r("photon", j);
  r.read_auto_or_positive("max_radius", p.max_radius);
  r.read("seed", p.seed);
  r.read("global_photons", p.global_photons, 1, kMaxPhotons);
  r.read("caustic_photons", p.caustic_photons, 1, kMaxPhotons);
  r.read("k", p.k, 1, kMaxK);
  r.read_enum("filter", p.filter,
              {{"box", DensityFilter::Box},
               {"cone", DensityFilter::Cone},
               {"biweight", DensityFilter::Biweight}});
  r.read("cone_k", p.cone_k, 1.0f, 1e6f);
  r.read("max_photon_depth", p.max_photon_depth, 1, 1000);
  r.read("final_gather_rays", p.final_gather_rays, 0, 65536);
  r.read_enum("photon_tree", p.photon_tree,
              {{"balanced", PhotonTreeKind::Balanced},
               {"sliding_midpoint", PhotonTreeKind::SlidingMidpoint},
               {"median_buckets", PhotonTreeKind::MedianBuckets},
               {"brute_force", PhotonTreeKind::BruteForce}});
  r.read("leaf_size", p.leaf_size, 1, 256);
  r.read("cull", p.cull);
  r.read("cache_distances", p.cache_distances);
  r.read("skip_unneeded_maps", p.skip_unneeded_maps);
  r.finish();
}

}  // namespace photon
