#pragma once
// The k-nearest-neighbour gather over a photon map: its knobs, its result and its counters.
//
// A gather returns the k photons nearest to a query point among those closer than max_radius
// (squared distance < max_radius^2), ordered by (squared distance, photon index): at equal
// distance the lower original index wins, so every tree variant and every switch that cannot
// change the answer returns the same photons, bit for bit. With `cull`, photons arriving from
// behind the surface (dot(direction, normal) >= 0) are rejected before they reach the heap.

#include "knobs/knob_table.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace photon {

/// Knobs of one gather (the paper's optimisations 2 and 3 are `cull` and `cache_distances`).
struct GatherParams {
  /// Photons gathered per lookup.
  int k = 50;
  /// Largest distance searched, world units (+inf: unbounded).
  float max_radius = 0.1f;
  /// Optimisation 2: reject photons from the back hemisphere of the query's normal before the
  /// heap. Changes the answer (k front-facing photons instead of k photons).
  bool cull = true;
  /// Optimisation 3: keep each photon's squared distance in the heap entry, computed once; off,
  /// every heap comparison recomputes it from the positions. Never changes the answer.
  bool cache_distances = true;

  static const knobs::KnobTable<GatherParams>& knobs();
};

/// Throws knobs::ConfigError naming the first knob out of range ("gather: knob 'k' must be
/// in [1, 1048576], got 0").
void validate(const GatherParams& p);

/// One photon found by a gather.
struct Neighbor {
  float d2 = 0.0f;          ///< Squared distance to the query, world units squared.
  std::uint32_t slot = 0;   ///< Index of the photon in its map's storage (PhotonMap::photon).
};

template <bool Count, bool Cull, bool Cache>
class GatherState;

/// The photons one gather found: a max-heap on (d2, index) once k were found (the farthest
/// first), in discovery order before that. Reused across gathers to avoid allocations.
class Neighbors {
 public:
  /// The photons found, at most k.
  std::span<const Neighbor> items() const { return {items_.data(), std::size_t(count_)}; }
  int size() const { return count_; }
  bool empty() const { return count_ == 0; }
  /// k of the gather that filled it.
  int k() const { return k_; }
  /// True when k photons were found within the radius.
  bool full() const { return count_ == k_ && k_ > 0; }
  /// Largest squared distance among the photons found (0 when none), world units squared.
  float max_d2() const {
    if (count_ > 0 && sorted_) return items_[count_ - 1].d2;
    if (full()) return items_[0].d2;
    float m = 0.0f;
    for (int i = 0; i < count_; ++i) m = items_[i].d2 > m ? items_[i].d2 : m;
    return m;
  }
  /// The query's max_radius squared, world units squared.
  float max_radius2() const { return max_radius2_; }
  /// Orders the photons by (d2, id(slot)), nearest first; `id` maps a slot to its original index
  /// (PhotonMap::original_index). The heap order is lost.
  template <class IdFn>
  void sort(IdFn&& id) {
    std::sort(items_.begin(), items_.begin() + count_, [&](const Neighbor& a, const Neighbor& b) {
      return a.d2 < b.d2 || (a.d2 == b.d2 && id(a.slot) < id(b.slot));
    });
    sorted_ = true;
  }

 private:
  template <bool Count, bool Cull, bool Cache>
  friend class GatherState;
  std::vector<Neighbor> items_;
  std::vector<std::uint64_t> keys_;   // the gather's heap: (d2 bits << 32 | original index)
  std::vector<std::uint32_t> slots_;  // and the storage slot of each entry
  int count_ = 0;
  int k_ = 0;
  float max_radius2_ = 0.0f;
  bool sorted_ = false;
};

/// Work done by gathers, counted only when the gather's `Count` template flag is set.
struct GatherCounters {
  std::uint64_t lookups = 0;         ///< Gathers run.
  std::uint64_t nodes_visited = 0;   ///< Tree nodes entered (balanced: photons; bucket: cells).
  std::uint64_t photons_tested = 0;  ///< Squared distances computed for candidate photons.
  std::uint64_t photons_culled = 0;  ///< Candidates within range rejected by the hemisphere test.
  std::uint64_t heap_inserts = 0;    ///< Photons that entered the heap.
  std::uint64_t photons_found = 0;   ///< Photons returned, summed over lookups.

  GatherCounters& operator+=(const GatherCounters& o) {
    lookups += o.lookups;
    nodes_visited += o.nodes_visited;
    photons_tested += o.photons_tested;
    photons_culled += o.photons_culled;
    heap_inserts += o.heap_inserts;
    photons_found += o.photons_found;
    return *this;
  }
};

void to_json(nlohmann::json& j, const GatherCounters& c);

}  // namespace photon
