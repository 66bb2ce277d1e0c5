#pragma once
// A photon map: photons stored in one of the photon-tree variants, answering k-nearest-neighbour
// gathers. The variant is a std::variant visited once per gather (or once around a whole loop
// with visit()), so each variant's search is compiled on its own; the gather switches select
// template instantiations, so the timed path carries no branch for them.

#include "balanced_tree.h"
#include "brute_force.h"
#include "bucket_tree.h"
#include "knn.h"
#include "neighbor_heap.h"
#include "photon.h"
#include "photon_tree_params.h"
#include "photon_tree_stats.h"

#include "accel/accel.h"

#include <cmath>
#include <cstdint>
#include <span>
#include <variant>
#include <vector>

namespace photon {

using AnyPhotonTree = std::variant<BruteForce, BalancedTree, BucketTree>;

class PhotonMap {
 public:
  /// An empty map: every gather finds nothing.
  PhotonMap() = default;
  /// Builds the tree `params` asks for over `photons` (original index = position in the span).
  /// Throws knobs::ConfigError for a bad knob, a photon with a non-finite position, more than
  /// 2^31 photons, or when the map would need more bytes than `limits` allow.
  PhotonMap(std::span<const Photon> photons, const PhotonTreeParams& params,
            const accel::BuildLimits& limits = {});
  // Move-only: photon() reads through pointers into the tree's storage.
  PhotonMap(PhotonMap&&) = default;
  PhotonMap& operator=(PhotonMap&&) = default;
  PhotonMap(const PhotonMap&) = delete;
  PhotonMap& operator=(const PhotonMap&) = delete;

  /// Photons stored.
  std::size_t size() const {
    return std::visit([](const auto& t) { return t.size(); }, tree_);
  }
  bool empty() const { return size() == 0; }
  const PhotonTreeParams& params() const { return params_; }
  const PhotonTreeStats& stats() const {
    return std::visit([](const auto& t) -> const PhotonTreeStats& { return t.stats(); }, tree_);
  }
  /// The photon in storage slot `slot` (a Neighbor's slot).
  const Photon& photon(std::uint32_t slot) const { return storage_[slot]; }
  /// The original index (position in the span it was built from) of the photon in `slot`.
  std::uint32_t original_index(std::uint32_t slot) const { return ids_ ? ids_[slot] : slot; }
  /// The tree itself, for code that dispatches once around a loop of gathers.
  const AnyPhotonTree& tree() const { return tree_; }

  /// The k nearest photons to `position` within params.max_radius (knn.h); with params.cull,
  /// only photons arriving from the side `normal` points to (a zero normal culls nothing). A
  /// position with a non-finite coordinate finds nothing.
  /// Count: add the work done to *counters. Throws knobs::ConfigError for a bad knob.
  template <bool Count = false>
  void gather(const Vec3& position, const Vec3& normal, const GatherParams& params,
              Neighbors& out, GatherCounters* counters = nullptr) const {
    validate(params);
    std::visit([&](const auto& t) { gather_in<Count>(t, position, normal, params, out, counters); },
               tree_);
  }

  /// gather() on one known variant, without the variant dispatch (params already validated).
  template <bool Count = false, class Tree>
  static void gather_in(const Tree& tree, const Vec3& position, const Vec3& normal,
                        const GatherParams& params, Neighbors& out, GatherCounters* counters) {
    if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z)) {
      // No photon has a distance to such a point: nothing is found.
      GatherState<Count, false, true>(tree.storage().data(), tree.ids(), Vec3(0.0f), normal,
                                      params.k, params.max_radius, out, counters)
          .finish();
      return;
    }
    const bool cull = params.cull && (normal.x != 0.0f || normal.y != 0.0f || normal.z != 0.0f);
    if (cull) {
      if (params.cache_distances)
        run<Count, true, true>(tree, position, normal, params, out, counters);
      else
        run<Count, true, false>(tree, position, normal, params, out, counters);
    } else {
      if (params.cache_distances)
        run<Count, false, true>(tree, position, normal, params, out, counters);
      else
        run<Count, false, false>(tree, position, normal, params, out, counters);
    }
  }

 private:
  template <bool Count, bool Cull, bool Cache, class Tree>
  static void run(const Tree& tree, const Vec3& position, const Vec3& normal,
                  const GatherParams& params, Neighbors& out, GatherCounters* counters) {
    GatherState<Count, Cull, Cache> s(tree.storage().data(), tree.ids(), position, normal,
                                      params.k, params.max_radius, out, counters);
    tree.search(s);
    s.finish();
  }

  AnyPhotonTree tree_;
  PhotonTreeParams params_;
  const Photon* storage_ = nullptr;
  const std::uint32_t* ids_ = nullptr;
};

}  // namespace photon
