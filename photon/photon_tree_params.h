#pragma once
// Which tree a photon map is built as (the paper's optimisation 1 is `balanced`), and its knobs.

#include "knobs/knob_table.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace photon {

/// The photon kd-tree variants.
enum class PhotonTreeKind : std::uint8_t {
  /// The paper's tree (Jensen 1996): every photon a node, split at the median of the cell's
  /// longest axis, stored as a left-balanced heap (children of node i at 2i and 2i+1).
  Balanced,
  /// Unbalanced: split the cell's longest axis at its midpoint, sliding the plane to the nearest
  /// photon when one side would be empty (Maneewongvatana and Mount 1999); photons in leaf
  /// buckets of at most `leaf_size`.
  SlidingMidpoint,
  /// Balanced with leaf buckets: the median of the cell's longest axis, as `balanced`, but the
  /// nodes, leaves and search of `sliding_midpoint`; the two differ only in balance.
  MedianBuckets,
  /// No tree: every photon tested. The reference of the tests and benchmarks.
  BruteForce,
};

/// Knobs of a photon map's tree.
struct PhotonTreeParams {
  /// Tree variant (JSON: "balanced", "sliding_midpoint", "median_buckets", "brute_force").
  PhotonTreeKind photon_tree = PhotonTreeKind::Balanced;
  /// Bucket trees: a cell with this many photons or fewer is a leaf, photons. 16: on
  /// a diffuse-only Cornell-box stand-in, leaves of 12 to 32 gathered within a few per cent of
  /// each other for k = 1..200 and 10^4..10^6 photons, 8 was 10-25 % slower
  /// (docs/photon-kdtree.md).
  int leaf_size = 16;
  /// Threads building a balanced tree, 0 = one per core; the tree is the same for any
  /// count. (The bucket trees build on one thread.)
  int build_threads = 0;

  static const knobs::KnobTable<PhotonTreeParams>& knobs();
};

/// The JSON spelling of a variant.
std::string_view name_of(PhotonTreeKind k);

/// The variants as knob choices (spelling, value), in display order.
std::vector<std::pair<std::string, PhotonTreeKind>> photon_tree_choices();

/// Throws knobs::ConfigError naming the first knob out of range.
void validate(const PhotonTreeParams& p);

}  // namespace photon
