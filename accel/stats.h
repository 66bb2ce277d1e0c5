#pragma once
// Statistics of a built structure and per-ray traversal counters.

#include <nlohmann/json.hpp>

#include <cstdint>

namespace accel {

/// Facts about a built structure, reported next to its timings.
struct BuildStats {
  double build_ms = 0.0;            ///< Wall-clock build time, milliseconds.
  std::uint64_t nodes = 0;          ///< Nodes stored, inner and leaf.
  std::uint64_t leaves = 0;         ///< Leaf nodes stored.
  std::uint64_t empty_leaves = 0;   ///< Stored leaves that hold no primitive.
  std::uint64_t prim_refs = 0;      ///< Primitive references over all nodes (>= primitives).
  std::uint64_t primitives = 0;     ///< Distinct primitives the structure was built over.
  int max_depth_reached = 0;        ///< Deepest node, root = 0.
  double mean_leaf_prims = 0.0;     ///< Mean primitives per non-empty leaf.
  std::uint64_t max_leaf_prims = 0; ///< Largest leaf, primitives.
  std::uint64_t memory_bytes = 0;   ///< Bytes held by nodes and reference arrays.
  double sah_cost = 0.0;            ///< SAH cost of the tree (traversal cost 1, intersection cost 1).

  /// prim_refs / primitives: 1.0 when every primitive is stored once.
  double duplication() const {
    return primitives ? double(prim_refs) / double(primitives) : 1.0;
  }
};

/// Accumulates the leaf statistics of a tree while it is built; finish() derives the mean.
class LeafTally {
 public:
  /// Records a leaf holding `prims` primitives whose box has `area_fraction` of the root's area
  /// (its contribution to the SAH cost, intersection cost 1).
  void add(BuildStats& s, std::uint64_t prims, double area_fraction) {
    s.leaves++;
    if (prims == 0) s.empty_leaves++;
    leaf_prims_ += prims;
    if (prims > s.max_leaf_prims) s.max_leaf_prims = prims;
    s.sah_cost += area_fraction * double(prims);
  }
  /// Mean primitives over the non-empty leaves.
  void finish(BuildStats& s) const {
    const std::uint64_t full = s.leaves - s.empty_leaves;
    s.mean_leaf_prims = full ? double(leaf_prims_) / double(full) : 0.0;
  }

 private:
  std::uint64_t leaf_prims_ = 0;
};

/// Per-ray work, gathered only in a counting pass (traversal's `Count` template flag).
struct TraversalCounters {
  std::uint64_t rays = 0;           ///< Queries answered.
  std::uint64_t nodes_visited = 0;  ///< Nodes popped or descended into.
  std::uint64_t boxes_tested = 0;   ///< Slab tests performed.
  std::uint64_t prims_tested = 0;   ///< Leaf callbacks invoked.

  TraversalCounters& operator+=(const TraversalCounters& o) {
    rays += o.rays;
    nodes_visited += o.nodes_visited;
    boxes_tested += o.boxes_tested;
    prims_tested += o.prims_tested;
    return *this;
  }
};

inline void to_json(nlohmann::json& j, const BuildStats& s) {
  j = {{"build_ms", s.build_ms},           {"nodes", s.nodes},
       {"leaves", s.leaves},               {"empty_leaves", s.empty_leaves},
       {"prim_refs", s.prim_refs},         {"primitives", s.primitives},
       {"duplication", s.duplication()},   {"max_depth_reached", s.max_depth_reached},
       {"mean_leaf_prims", s.mean_leaf_prims}, {"max_leaf_prims", s.max_leaf_prims},
       {"memory_bytes", s.memory_bytes},   {"sah_cost", s.sah_cost}};
}

inline void to_json(nlohmann::json& j, const TraversalCounters& c) {
  const double n = c.rays ? double(c.rays) : 1.0;
  j = {{"rays", c.rays},
       {"nodes_visited", c.nodes_visited},
       {"boxes_tested", c.boxes_tested},
       {"prims_tested", c.prims_tested},
       {"nodes_per_ray", double(c.nodes_visited) / n},
       {"boxes_per_ray", double(c.boxes_tested) / n},
       {"prims_per_ray", double(c.prims_tested) / n}};
}

}  // namespace accel
