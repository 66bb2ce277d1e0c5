#pragma once
// No tree: the photons in their original order, each one offered to every gather. The
// reference that every tree variant must match exactly.

#include "photon.h"
#include "photon_tree_stats.h"

#include <chrono>
#include <cstdint>
#include <span>
#include <vector>

namespace photon {

class BruteForce {
 public:
  BruteForce() = default;
  explicit BruteForce(std::span<const Photon> photons) : photons_(photons.begin(), photons.end()) {
    for (Photon& p : photons_) p.flags = 3;
    stats_.photons = stats_.max_leaf_photons = photons_.size();
    stats_.nodes = stats_.leaves = photons_.empty() ? 0 : 1;
    stats_.depth = photons_.empty() ? 0 : 1;
    stats_.memory_bytes = photons_.capacity() * sizeof(Photon);
  }

  /// Photons in their original order.
  std::span<const Photon> storage() const { return photons_; }
  /// nullptr: a slot is the original index.
  const std::uint32_t* ids() const { return nullptr; }
  std::size_t size() const { return photons_.size(); }
  const PhotonTreeStats& stats() const { return stats_; }

  template <class State>
  void search(State& s) const {
    s.count_node();
    const std::uint32_t n = std::uint32_t(photons_.size());
    for (std::uint32_t i = 0; i < n; ++i) s.consider(i);
  }

 private:
  std::vector<Photon> photons_;
  PhotonTreeStats stats_;
};

}  // namespace photon
