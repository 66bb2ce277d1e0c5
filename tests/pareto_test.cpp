// Pareto front marking (harness/pareto.h): no dominated point on the front, no non-dominated point
// missed, on hand-made data and against brute force on random data.

#include "harness/pareto.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

using harness::TimeError;

std::vector<bool> brute_force(const std::vector<TimeError>& p) {
  std::vector<bool> on(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const bool ok = std::isfinite(p[i].time) && std::isfinite(p[i].error) && p[i].time >= 0 && p[i].error >= 0;
    on[i] = ok;
    for (std::size_t j = 0; j < p.size() && on[i]; ++j)
      if (harness::dominates(p[j], p[i])) on[i] = false;
  }
  return on;
}

TEST(Pareto, HandMade) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<TimeError> p = {
      {10, 1.0},   // 0 front: fastest
      {20, 0.5},   // 1 front
      {25, 0.6},   // 2 dominated by 1
      {20, 0.7},   // 3 dominated by 1 (same time, worse error)
      {40, 0.1},   // 4 front: most accurate
      {40, 0.1},   // 5 equal to 4: on the front too
      {50, 0.1},   // 6 dominated by 4 (slower, same error)
      {5, nan},    // 7 broken: off, dominates nothing
      {30, 0.5},   // 8 dominated by 1 (slower, same error)
      {12, 0.9},   // 9 front
      {-1, 0.0},   // 10 negative time: unusable
  };
  const std::vector<bool> want = {true, true, false, false, true, true, false, false, false, true, false};
  EXPECT_EQ(harness::pareto_front(p), want);
  EXPECT_EQ(harness::pareto_indices(p), (std::vector<std::size_t>{0, 9, 1, 4, 5}));
  EXPECT_TRUE(harness::pareto_front({}).empty());
}

TEST(Pareto, MatchesBruteForceOnRandomPoints) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> coarse(0, 9);  // many ties in both coordinates
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<TimeError> p(std::size_t(1 + trial % 40));
    for (auto& q : p) q = {double(coarse(rng)), double(coarse(rng)) * 0.1};
    const std::vector<bool> on = harness::pareto_front(p);
    ASSERT_EQ(on, brute_force(p)) << "trial " << trial;
    // The defining properties, directly: nothing on the front is dominated, and everything off
    // the front is dominated by a front point.
    for (std::size_t i = 0; i < p.size(); ++i) {
      bool dominated = false, by_front = false;
      for (std::size_t j = 0; j < p.size(); ++j)
        if (harness::dominates(p[j], p[i])) {
          dominated = true;
          by_front = by_front || on[j];
        }
      EXPECT_EQ(on[i], !dominated);
      if (dominated) {
        EXPECT_TRUE(by_front);
      }
    }
  }
}

}  // namespace
