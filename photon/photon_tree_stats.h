#pragma once
// Facts about a built photon tree, reported next to its timings.

#include <nlohmann/json.hpp>

#include <cstdint>

namespace photon {

struct PhotonTreeStats {
  double build_ms = 0.0;            ///< Wall-clock build time, milliseconds.
  std::uint64_t photons = 0;        ///< Photons stored.
  std::uint64_t nodes = 0;          ///< Tree nodes (balanced: one per photon; bucket: cells).
  std::uint64_t leaves = 0;         ///< Leaf nodes.
  int depth = 0;                    ///< Levels, root = 1 (0 for an empty tree).
  std::uint64_t max_leaf_photons = 0;  ///< Largest leaf, photons.
  std::uint64_t memory_bytes = 0;   ///< Bytes held by photons, ids and nodes.
};

inline void to_json(nlohmann::json& j, const PhotonTreeStats& s) {
  j = {{"build_ms", s.build_ms}, {"photons", s.photons},
       {"nodes", s.nodes},       {"leaves", s.leaves},
       {"depth", s.depth},       {"max_leaf_photons", s.max_leaf_photons},
       {"memory_bytes", s.memory_bytes}};
}

}  // namespace photon
