#include "photon_map.h"

#include <cmath>
#include <limits>
#include <string>

namespace photon {

namespace {

/// Bytes a build holds at its peak: the input is not counted (the caller owns it); the tree's
/// photons and ids plus the builder's 16-byte items, and for bucket trees up to 2N/leaf nodes.
std::uint64_t peak_bytes(std::uint64_t n, const PhotonTreeParams& p) {
  switch (p.photon_tree) {
    case PhotonTreeKind::BruteForce:
      return n * sizeof(Photon);
    case PhotonTreeKind::Balanced:
      return (n + 1) * (sizeof(Photon) + 4) + n * 16;
    case PhotonTreeKind::SlidingMidpoint:
    case PhotonTreeKind::MedianBuckets:
      return n * (sizeof(Photon) + 4 + 16) + (2 * n / std::uint64_t(p.leaf_size) + 2) * 8;
  }
  return 0;
}

}  // namespace

PhotonMap::PhotonMap(std::span<const Photon> photons, const PhotonTreeParams& params,
                     const accel::BuildLimits& limits)
    : params_(params) {
  validate(params);
  if (photons.size() > std::size_t(std::numeric_limits<std::int32_t>::max()))
    throw knobs::ConfigError("photon map: " + std::to_string(photons.size()) +
                             " photons, more than the 2^31 - 1 a map can index");
  const std::uint64_t need = peak_bytes(photons.size(), params);
  const std::uint64_t budget = accel::memory_budget_bytes(limits);
  if (need > budget)
    throw knobs::ConfigError("photon map: " + std::to_string(photons.size()) + " photons need " +
                             std::to_string(need >> 20) + " MiB, more than the memory budget of " +
                             std::to_string(budget >> 20) + " MiB (--max-memory)");
  for (std::size_t i = 0; i < photons.size(); ++i) {
    const Vec3& p = photons[i].position;
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw knobs::ConfigError("photon map: photon " + std::to_string(i) +
                               " has a non-finite position");
  }
  switch (params.photon_tree) {
    case PhotonTreeKind::BruteForce:
      tree_.emplace<BruteForce>(photons);
      break;
    case PhotonTreeKind::Balanced:
      tree_.emplace<BalancedTree>(photons, params.build_threads);
      break;
    case PhotonTreeKind::SlidingMidpoint:
      tree_ = BucketTree::sliding_midpoint(photons, params.leaf_size);
      break;
    case PhotonTreeKind::MedianBuckets:
      tree_ = BucketTree::median(photons, params.leaf_size);
      break;
  }
  std::visit(
      [&](const auto& t) {
        storage_ = t.storage().data();
        ids_ = t.ids();
      },
      tree_);
}

}  // namespace photon
