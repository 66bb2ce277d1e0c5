// The bucket trees (photon/bucket_tree.h), sliding midpoint and median: every photon in exactly
// one leaf, inside its cell, leaves within leaf_size except cells of coincident photons; the
// median tree as shallow as halving allows.

#include "photon/bucket_tree.h"

#include "photon_sets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace {

using photon::BucketTree;
using photon::Photon;
using photon_sets::SetKind;

struct Walk {
  const BucketTree& t;
  int leaf_size;
  std::vector<int> seen;
  std::string error;
  int max_depth = 0;

  void node(std::uint32_t i, const accel::Aabb& cell, int depth) {
    if (!error.empty()) return;
    max_depth = std::max(max_depth, depth + 1);
    const accel::KdNode n = t.nodes()[i];
    if (n.is_leaf()) {
      bool coincident = true;
      for (std::uint32_t s = n.prim_begin(); s < n.prim_begin() + n.prim_count(); ++s) {
        const Photon& p = t.storage()[s];
        seen[t.ids()[s]]++;
        coincident = coincident && p.position == t.storage()[n.prim_begin()].position;
        for (int a = 0; a < 3; ++a)
          if (p.position[a] < cell.lo[a] || p.position[a] > cell.hi[a]) error = "photon outside its leaf";
      }
      if (int(n.prim_count()) > leaf_size && !coincident) error = "oversized leaf";
      if (n.prim_count() == 0) error = "empty leaf";
      return;
    }
    accel::Aabb lower = cell, upper = cell;
    if (n.split() < cell.lo[n.axis()] || n.split() > cell.hi[n.axis()]) error = "split outside its cell";
    lower.hi[n.axis()] = n.split();
    upper.lo[n.axis()] = n.split();
    node(i + 1, lower, depth + 1);
    node(n.upper_child(), upper, depth + 1);
  }
};

TEST(BucketTree, EveryPhotonOnceInsideItsLeaf) {
  for (const bool median : {false, true}) {
    for (const SetKind kind : photon_sets::kAllKinds) {
      for (const int leaf : {1, 4, 16}) {
        for (const std::size_t n : {1u, 2u, 5u, 17u, 1000u, 20000u}) {
          const auto photons = photon_sets::make_set(kind, n, std::uint32_t(n + leaf));
          const BucketTree t = median ? BucketTree::median(photons, leaf)
                                      : BucketTree::sliding_midpoint(photons, leaf);
          const std::string label = std::string(median ? "median " : "sliding_midpoint ") +
                                    photon_sets::name_of(kind) + " leaf " + std::to_string(leaf) +
                                    " N=" + std::to_string(n);
          Walk w{t, leaf, std::vector<int>(n, 0), "", 0};
          w.node(0, t.bounds(), 0);
          ASSERT_EQ(w.error, "") << label;
          EXPECT_EQ(std::count(w.seen.begin(), w.seen.end(), 1), std::ptrdiff_t(n)) << label;
          EXPECT_EQ(w.max_depth, t.stats().depth) << label;
          EXPECT_LE(t.stats().depth, BucketTree::kMaxDepth + 1) << label;
          EXPECT_EQ(t.stats().nodes, t.nodes().size()) << label;
          if (median) {
            // Halving: a cell of c > leaf photons has children of floor(c/2) and ceil(c/2).
            int levels = 1;
            for (std::size_t c = n; c > std::size_t(leaf); c = (c + 1) / 2) ++levels;
            EXPECT_LE(t.stats().depth, levels) << label;
          }
        }
      }
    }
  }
}

TEST(BucketTree, CoincidentPhotonsMakeOneLeaf) {
  std::vector<Photon> same(1000, Photon::make(photon::Vec3(0.5f), photon::Color(1.0f), photon::Vec3(0, 0, -1)));
  const BucketTree t = BucketTree::sliding_midpoint(same, 8);
  EXPECT_EQ(t.nodes().size(), 1u);
  EXPECT_EQ(t.stats().max_leaf_photons, 1000u);
}

TEST(BucketTree, EmptyTree) {
  const BucketTree t = BucketTree::median(std::vector<Photon>{}, 8);
  EXPECT_EQ(t.size(), 0u);
  EXPECT_TRUE(t.nodes().empty());
}

}  // namespace
