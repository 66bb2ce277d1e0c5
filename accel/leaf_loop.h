#pragma once
// The leaf loop every structure shares: the traversal contract's leaf function called on a run
// of primitive ids, in order, with the any-hit exit and the counter in one place.

#include "geometry.h"
#include "stats.h"

#include <cstdint>

namespace accel {

/// Calls leaf_fn(ids[i], ray) for i in [0, count), in order. A call returning true sets `hit`;
/// with AnyHit it ends the loop and test_leaf returns true (the query is answered). Returns
/// false otherwise. Counts one primitive test per call when Count.
template <bool Count, bool AnyHit, class LeafFn>
inline bool test_leaf(const std::uint32_t* ids, std::uint32_t count, Ray& ray, LeafFn& leaf_fn,
                      TraversalCounters* counters, bool& hit) {
  for (std::uint32_t i = 0; i < count; ++i) {
    if constexpr (Count) counters->prims_tested++;
    if (leaf_fn(ids[i], ray)) {
      if constexpr (AnyHit) return true;
      hit = true;
    }
  }
  return false;
}

}  // namespace accel
