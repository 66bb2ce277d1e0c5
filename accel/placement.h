#pragma once
// Where a tree stores a primitive that overlaps several children: the paper's two policies,
// shared by the octree and the kd-tree.

#include "knobs/knob_table.h"

#include <cstdint>

namespace accel {

enum class Placement : std::uint8_t {
  /// A primitive is referenced by every leaf it overlaps (it may be stored many times).
  Leaves,
  /// A primitive that straddles a node's split stays in that node and is stored once (the
  /// paper's fix for the duplication of `Leaves`).
  EveryLevel,
};

/// The knob spelling of a placement: "leaves" or "every_level".
inline const char* placement_name(Placement p) {
  return p == Placement::Leaves ? "leaves" : "every_level";
}

/// The `placement` knob of a tree whose parameter struct P stores it in `member`.
template <class P>
knobs::Knob<P> placement_knob(Placement P::*member) {
  return knobs::Knob<P>::choice("placement", member,
                         {{placement_name(Placement::Leaves), Placement::Leaves},
                          {placement_name(Placement::EveryLevel), Placement::EveryLevel}},
                         "Where a primitive overlapping several children is stored: in every leaf it "
                         "overlaps, or once, at the node whose split it straddles (the paper's fix).")
      .variant()
      .shorthand();
}

}  // namespace accel
