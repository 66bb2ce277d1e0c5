// The binned SAH split search (accel/binned_sah.h): its partition reorders the boxes exactly as
// std::partition reorders ids with the same predicate (so the builders make the trees the
// id-based builder made), and the bounds it returns for both sides are those of their boxes.

#include "accel/binned_sah.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

namespace {

using accel::Aabb;
using accel::BinnedSah;
using accel::Vec3;

std::vector<Aabb> random_boxes(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-100.0f, 100.0f), size(0.0f, 3.0f);
  std::vector<Aabb> boxes(n);
  for (Aabb& b : boxes) {
    const Vec3 lo(pos(rng), pos(rng), pos(rng));
    b = {lo, lo + Vec3(size(rng), size(rng), size(rng))};
  }
  return boxes;
}

/// The bounds of boxes[ids[begin..end)], computed from scratch.
BinnedSah::Bounds bounds_of(const std::vector<Aabb>& boxes, const std::vector<std::uint32_t>& ids, std::size_t begin,
                            std::size_t end) {
  BinnedSah::Bounds b;
  for (std::size_t i = begin; i < end; ++i) {
    b.box.grow(boxes[ids[i]]);
    b.centroids.grow(boxes[ids[i]].center());
  }
  return b;
}

void expect_same(const Aabb& a, const Aabb& b) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(a.lo[k], b.lo[k]);
    EXPECT_EQ(a.hi[k], b.hi[k]);
  }
}

TEST(BinnedSah, PartitionsLikeStdPartitionAndBoundsBothSides) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const std::vector<Aabb> boxes = random_boxes(1000 + seed * 37, seed);
    const auto n = std::uint32_t(boxes.size());
    BinnedSah sah(boxes, 16, 3.0f);
    std::vector<std::uint32_t> ids(n);
    std::iota(ids.begin(), ids.end(), 0u);
    // Split the whole range, then its left part, as a builder would.
    std::uint32_t begin = 0, end = n;
    BinnedSah::Bounds whole = sah.bounds(begin, end);
    for (int level = 0; level < 4; ++level) {
      SCOPED_TRACE(level);
      const BinnedSah::Bounds fresh = bounds_of(boxes, ids, begin, end);
      expect_same(whole.box, fresh.box);
      expect_same(whole.centroids, fresh.centroids);
      const BinnedSah::Split split = sah.find(begin, end, whole.centroids, whole.box.half_area());
      ASSERT_GE(split.axis, 0);
      // The same predicate the search partitions by: the split's bin of each centroid.
      const int axis = split.axis;
      const float lo = whole.centroids.lo[axis];
      const float scale = 16.0f / (whole.centroids.hi[axis] - whole.centroids.lo[axis]);
      const auto goes_left = [&](std::uint32_t id) {
        return std::clamp(int((boxes[id].center()[axis] - lo) * scale), 0, 15) < split.bin;
      };
      const auto expected_mid = std::uint32_t(std::partition(ids.begin() + begin, ids.begin() + end, goes_left) - ids.begin());
      BinnedSah::Bounds left, right;
      const std::uint32_t mid = sah.partition(begin, end, whole.centroids, split, left, right);
      ASSERT_EQ(mid, expected_mid);
      ASSERT_GT(mid, begin);
      ASSERT_LT(mid, end);
      std::vector<std::uint32_t> got;
      sah.copy_ids(got);
      EXPECT_EQ(got, ids);
      const BinnedSah::Bounds l = bounds_of(boxes, ids, begin, mid), r = bounds_of(boxes, ids, mid, end);
      expect_same(left.box, l.box);
      expect_same(left.centroids, l.centroids);
      expect_same(right.box, r.box);
      expect_same(right.centroids, r.centroids);
      end = mid;
      whole = left;
    }
  }
}

TEST(BinnedSah, CoincidentCentroidsAreCutInHalfInOrder) {
  const std::vector<Aabb> boxes(10, Aabb{Vec3(1.0f), Vec3(2.0f)});
  BinnedSah sah(boxes, 16, 3.0f);
  const BinnedSah::Bounds whole = sah.bounds(0, 10);
  const BinnedSah::Split split = sah.find(0, 10, whole.centroids, whole.box.half_area());
  EXPECT_EQ(split.axis, -1);
  BinnedSah::Bounds left, right;
  EXPECT_EQ(sah.partition(0, 10, whole.centroids, split, left, right), 5u);
  expect_same(left.box, whole.box);
  expect_same(right.box, whole.box);
}

}  // namespace
