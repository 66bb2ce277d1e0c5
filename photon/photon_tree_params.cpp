#include "photon_tree_params.h"

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

std::vector<std::pair<std::string, PhotonTreeKind>> photon_tree_choices() {
  std::vector<std::pair<std::string, PhotonTreeKind>> out;
  for (const auto& [name, kind] : kKinds) out.emplace_back(name, kind);
  return out;
}

const knobs::KnobTable<PhotonTreeParams>& PhotonTreeParams::knobs() {
  using K = knobs::Knob<PhotonTreeParams>;
  static const knobs::KnobTable<PhotonTreeParams> table(
      "photon map",
      {K::choice("photon_tree", &PhotonTreeParams::photon_tree, photon_tree_choices(),
                 "Photon kd-tree: the paper's balanced heap, or leaf buckets split at the sliding "
                 "midpoint or the median, or none (brute force); the image is the same for each.")
           .variant(),
       K::integer("leaf_size", &PhotonTreeParams::leaf_size, 1, kMaxLeafSize, "photons",
                  "Bucket trees: a cell with this many photons or fewer is a leaf."),
       K::integer("build_threads", &PhotonTreeParams::build_threads, 0, 256, "threads",
                  "Threads building a balanced tree (0 = one per core); the tree is the same for any count.")});
  return table;
}

void validate(const PhotonTreeParams& p) { PhotonTreeParams::knobs().validate(p); }

}  // namespace photon
