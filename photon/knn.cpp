#include "knn.h"

#include "accel/params_json.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace photon {

namespace {
constexpr int kMaxK = 1 << 20;
}  // namespace

void to_json(nlohmann::json& j, const GatherParams& p) {
  j = {{"k", p.k},
       {"max_radius", std::isinf(p.max_radius) ? nlohmann::json("inf") : nlohmann::json(p.max_radius)},
       {"cull", p.cull},
       {"cache_distances", p.cache_distances}};
}

void from_json(const nlohmann::json& j, GatherParams& p) {
  // max_radius is a number > 0, or "inf" for an unbounded search: read here, the rest by the
  // generic reader.
  nlohmann::json rest = j;
  if (rest.is_object() && rest.contains("max_radius")) {
    const nlohmann::json& v = rest["max_radius"];
    if (v == "inf") {
      p.max_radius = std::numeric_limits<float>::infinity();
    } else if (v.is_number() && v.get<double>() > 0.0 &&
               v.get<double>() <= std::numeric_limits<float>::max()) {
      p.max_radius = v.get<float>();
    } else {
      throw accel::ConfigError("gather: parameter 'max_radius' must be a number > 0 or \"inf\", got " +
                               v.dump());
    }
    rest.erase("max_radius");
  }
  accel::KnobReader r("gather", rest);
  r.read("k", p.k, 1, kMaxK);
  r.read("cull", p.cull);
  r.read("cache_distances", p.cache_distances);
  r.finish();
  validate(p);
}

void validate(const GatherParams& p) {
  if (p.k < 1 || p.k > kMaxK)
    throw accel::ConfigError("gather: k must be in [1, " + std::to_string(kMaxK) + "], got " +
                             std::to_string(p.k));
  if (!(p.max_radius > 0.0f)) {
    std::ostringstream s;
    s << "gather: max_radius must be > 0, got " << p.max_radius;
    throw accel::ConfigError(s.str());
  }
}

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
