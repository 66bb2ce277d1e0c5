// bench/bootstrap.h: percentile-bootstrap intervals of medians and of ratios of medians paired
// by round. A drift shared by a round cancels in the paired ratio; the same samples give the
// same interval every time.

#include "bench/bootstrap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace {

TEST(Bootstrap, MedianOf) {
  EXPECT_DOUBLE_EQ(bench::median_of({3.0, 1.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(bench::median_of({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_THROW(bench::median_of({}), std::invalid_argument);
}

TEST(Bootstrap, ADriftSharedByEachRoundCancelsInThePairedRatio) {
  // The machine slows down by up to 2x over the run; every round's renders share the slowdown.
  std::vector<double> naive, fast;
  for (int r = 0; r < 9; ++r) {
    const double drift = 1.0 + double(r) / 8.0;
    naive.push_back(1000.0 * drift);
    fast.push_back(10.0 * drift);
  }
  const bench::Interval paired = bench::ratio_of_medians_interval(naive, fast);
  EXPECT_DOUBLE_EQ(paired.lo, 100.0);
  EXPECT_DOUBLE_EQ(paired.hi, 100.0);
  // Unpaired (naive timed at the start, the structure at the end, as the sweep once did): the
  // same drift now decides the answer, and the interval of the ratio is wide.
  std::vector<double> early(naive.begin(), naive.begin() + 3), late(fast.end() - 3, fast.end());
  const double ratio = bench::median_of(early) / bench::median_of(late);
  EXPECT_LT(ratio, 70.0);  // 100 is the truth: drift made it 60
  // The time of one contender alone drifts: its median's interval is wide.
  const bench::Interval alone = bench::median_interval(fast);
  EXPECT_GT(alone.relative_width(bench::median_of(fast)), 0.3);
}

TEST(Bootstrap, IntervalsHoldThePointAndNarrowWithMoreRounds) {
  std::mt19937_64 rng(7);
  std::lognormal_distribution<double> noise(0.0, 0.05);
  auto rounds = [&](int n) {
    std::vector<double> a, b;
    for (int r = 0; r < n; ++r) {
      a.push_back(200.0 * noise(rng));
      b.push_back(20.0 * noise(rng));
    }
    return std::make_pair(a, b);
  };
  const auto [a5, b5] = rounds(5);
  const auto [a45, b45] = rounds(45);
  const bench::Interval i5 = bench::ratio_of_medians_interval(a5, b5);
  const bench::Interval i45 = bench::ratio_of_medians_interval(a45, b45);
  for (const auto& [i, a, b] : {std::tuple{i5, a5, b5}, std::tuple{i45, a45, b45}}) {
    const double point = bench::median_of(a) / bench::median_of(b);
    EXPECT_LE(i.lo, point);
    EXPECT_GE(i.hi, point);
  }
  EXPECT_LT(i45.hi - i45.lo, i5.hi - i5.lo);
  EXPECT_GT(i45.lo, 9.0);  // the truth, 10, inside a narrow interval
  EXPECT_LT(i45.hi, 11.0);
  // Deterministic: the same samples give the same interval.
  const bench::Interval again = bench::ratio_of_medians_interval(a5, b5);
  EXPECT_EQ(again.lo, i5.lo);
  EXPECT_EQ(again.hi, i5.hi);
  EXPECT_THROW(bench::ratio_of_medians_interval({1.0}, {1.0, 2.0}), std::invalid_argument);
}

}  // namespace
