#include "knn.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace photon {

namespace {
constexpr int kMaxK = 1 << 20;
}  // namespace

const knobs::KnobTable<GatherParams>& GatherParams::knobs() {
  using K = knobs::Knob<GatherParams>;
  static const knobs::KnobTable<GatherParams> table(
      "gather",
      {K::integer("k", &GatherParams::k, 1, kMaxK, "photons", "Photons gathered per lookup."),
       K::number_or_infinity("max_radius", &GatherParams::max_radius, 0.0, "world units",
                             "Largest distance searched; \"inf\" searches without bound.")
           .open_below(),
       K::boolean("cull", &GatherParams::cull,
                  "Optimisation 2: reject photons from behind the query's surface before the heap."),
       K::boolean("cache_distances", &GatherParams::cache_distances,
                  "Optimisation 3: compute each photon's squared distance once (never changes the answer).")});
  return table;
}

void validate(const GatherParams& p) { GatherParams::knobs().validate(p); }

void to_json(nlohmann::json& j, const GatherCounters& c) {
  const double n = c.lookups ? double(c.lookups) : 1.0;
  j = {{"lookups", c.lookups},
       {"nodes_visited", c.nodes_visited},
       {"photons_tested", c.photons_tested},
       {"photons_culled", c.photons_culled},
       {"heap_inserts", c.heap_inserts},
       {"photons_found", c.photons_found},
       {"nodes_per_lookup", double(c.nodes_visited) / n},
       {"photons_tested_per_lookup", double(c.photons_tested) / n},
       {"photons_found_per_lookup", double(c.photons_found) / n}};
}

}  // namespace photon
