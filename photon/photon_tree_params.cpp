#include "photon_tree_params.h"

#include "accel/params_json.h"

#include <string>

namespace photon {

namespace {
constexpr std::pair<const char*, PhotonTreeKind> kKinds[] = {
    {"balanced", PhotonTreeKind::Balanced},
    {"sliding_midpoint", PhotonTreeKind::SlidingMidpoint},
    {"median_buckets", PhotonTreeKind::MedianBuckets},
    {"brute_force", PhotonTreeKind::BruteForce},
};
constexpr int kMaxLeafSize = 256;
}  // namespace

std::string_view name_of(PhotonTreeKind k) {
  for (const auto& [name, kind] : kKinds)
    if (kind == k) return name;
  return "?";
}

void to_json(nlohmann::json& j, const PhotonTreeParams& p) {
  j = {{"photon_tree", std::string(name_of(p.photon_tree))},
       {"leaf_size", p.leaf_size},
       {"build_threads", p.build_threads}};
}

void from_json(const nlohmann::json& j, PhotonTreeParams& p) {
  accel::KnobReader r("photon map", j);
  r.read_enum("photon_tree", p.photon_tree,
              {{kKinds[0].first, kKinds[0].second},
               {kKinds[1].first, kKinds[1].second},
               {kKinds[2].first, kKinds[2].second},
               {kKinds[3].first, kKinds[3].second}});
  r.read("leaf_size", p.leaf_size, 1, kMaxLeafSize);
  r.read("build_threads", p.build_threads, 0, 256);
  r.finish();
}

void validate(const PhotonTreeParams& p) {
  if (p.leaf_size < 1 || p.leaf_size > kMaxLeafSize)
    throw accel::ConfigError("photon map: leaf_size must be in [1, " +
                             std::to_string(kMaxLeafSize) + "], got " +
                             std::to_string(p.leaf_size));
  if (p.build_threads < 0 || p.build_threads > 256)
    throw accel::ConfigError("photon map: build_threads must be in [0, 256], got " +
                             std::to_string(p.build_threads));
  if (name_of(p.photon_tree) == "?")
    throw accel::ConfigError("photon map: photon_tree is not a known variant");
}

}  // namespace photon
