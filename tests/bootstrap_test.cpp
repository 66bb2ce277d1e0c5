// harness/bootstrap.h: percentile-bootstrap intervals of medians and of paired ratios (the median
// of the rounds' ratios). A drift shared by a round cancels in the paired ratio, also where the
// ratio of the medians keeps it; the same samples give the same interval every time.

#include "harness/bootstrap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace {

TEST(Bootstrap, MedianOf) {
  EXPECT_DOUBLE_EQ(harness::median_of({3.0, 1.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(harness::median_of({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_THROW(harness::median_of({}), std::invalid_argument);
}

TEST(Bootstrap, ADriftSharedByEachRoundCancelsInThePairedRatio) {
  // The machine slows down by up to 2x over the run; every round's renders share the slowdown.
  std::vector<double> naive, fast;
  for (int r = 0; r < 9; ++r) {
    const double drift = 1.0 + double(r) / 8.0;
    naive.push_back(1000.0 * drift);
    fast.push_back(10.0 * drift);
  }
  const harness::Interval paired = harness::paired_ratio_interval(naive, fast);
  EXPECT_DOUBLE_EQ(paired.lo, 100.0);
  EXPECT_DOUBLE_EQ(paired.hi, 100.0);
  // Unpaired (naive timed at the start, the structure at the end, as the sweep once did): the
  // same drift now decides the answer, and the interval of the ratio is wide.
  std::vector<double> early(naive.begin(), naive.begin() + 3), late(fast.end() - 3, fast.end());
  const double ratio = harness::median_of(early) / harness::median_of(late);
  EXPECT_LT(ratio, 70.0);  // 100 is the truth: drift made it 60
  // The time of one contender alone drifts: its median's interval is wide.
  const harness::Interval alone = harness::median_interval(fast);
  EXPECT_GT(alone.relative_width(harness::median_of(fast)), 0.3);
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
  const harness::Interval i5 = harness::paired_ratio_interval(a5, b5);
  const harness::Interval i45 = harness::paired_ratio_interval(a45, b45);
  for (const auto& [i, a, b] : {std::tuple{i5, a5, b5}, std::tuple{i45, a45, b45}}) {
    const double point = harness::paired_ratio(a, b);
    EXPECT_LE(i.lo, point);
    EXPECT_GE(i.hi, point);
  }
  EXPECT_LT(i45.hi - i45.lo, i5.hi - i5.lo);
  EXPECT_GT(i45.lo, 9.0);  // the truth, 10, inside a narrow interval
  EXPECT_LT(i45.hi, 11.0);
  // Deterministic: the same samples give the same interval.
  const harness::Interval again = harness::paired_ratio_interval(a5, b5);
  EXPECT_EQ(again.lo, i5.lo);
  EXPECT_EQ(again.hi, i5.hi);
  EXPECT_THROW(harness::paired_ratio_interval({1.0}, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(harness::paired_ratio({1.0}, {0.0}), std::invalid_argument);
}

// The paper sweep's failure on a VM slowed from outside for seconds at a time: naive (4 s a
// render) and a structure (50 ms) share each round, and a slow spell makes a round 35% slower for
// both. Rounds 0-3 are slow for both; in round 4 the spell catches naive's 4-second render but
// not the 50-ms one. Naive's median is now a slow sample and the structure's a fast one: the
// ratio of the medians is 35% too high, the median of the rounds' ratios is the truth.
TEST(Bootstrap, APairedRatioIgnoresASlowSpellThatOnlyTheLongRenderCaught) {
  std::vector<double> naive, fast;
  for (int r = 0; r < 9; ++r) {
    const double slow = r < 4 ? 1.35 : 1.0;
    const double jitter = 1.0 + 0.001 * r;  // distinct samples
    naive.push_back(4000.0 * jitter * slow * (r == 4 ? 1.35 : 1.0));
    fast.push_back(50.0 * jitter * slow);
  }
  EXPECT_GT(harness::median_of(naive) / harness::median_of(fast), 1.3 * 80.0);
  EXPECT_DOUBLE_EQ(harness::paired_ratio(naive, fast), 80.0);
  const harness::Interval i = harness::paired_ratio_interval(naive, fast);
  EXPECT_LE(i.lo, 80.0);
  EXPECT_GE(i.hi, 80.0);
}

}  // namespace
