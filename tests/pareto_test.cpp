// Pareto front marking (harness/pareto.h): no dominated point on the front, no non-dominated point
// missed, on hand-made data and against brute force on random data; unresolved points dominate
// only unresolved points.

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

// An unresolved point (its error cannot be told from the reference's own) is faster and measured
// more accurate than a resolved one: under the plain rule it would push the resolved point off
// the front; here it does not. It still beats the slower unresolved point, and a resolved point
// still beats the unresolved points it dominates.
TEST(Pareto, AnUnresolvedPointDoesNotBeatAResolvedOne) {
  const std::vector<TimeError> p = {
      {10, 0.015, false},  // 0 unresolved, fastest and most accurate: front
      {20, 0.040, true},   // 1 resolved: beaten only by the unresolved 0, so on the front
      {30, 0.020, false},  // 2 unresolved: dominated by the unresolved 0
      {40, 0.030, true},   // 3 resolved: only the unresolved 0 beats it, so on the front
      {50, 0.035, true},   // 4 resolved: dominated by the resolved 3
      {45, 0.050, false},  // 5 unresolved: dominated by the resolved 3 (and 0)
  };
  EXPECT_FALSE(harness::dominates(p[0], p[1]));
  EXPECT_TRUE(harness::dominates(p[0], p[2]));
  EXPECT_TRUE(harness::dominates(p[3], p[5]));
  EXPECT_TRUE(harness::dominates(p[3], p[4]));
  EXPECT_EQ(harness::pareto_front(p), (std::vector<bool>{true, true, false, true, false, false}));
  EXPECT_EQ(harness::pareto_indices(p), (std::vector<std::size_t>{0, 1, 3}));
  // The same points all resolved: the old rule, under which 0 beats 1 and 3.
  std::vector<TimeError> all = p;
  for (auto& q : all) q.resolved = true;
  EXPECT_EQ(harness::pareto_front(all), (std::vector<bool>{true, false, false, false, false, false}));
  // Equal time and error, one resolved and one not: neither dominates the other.
  const std::vector<TimeError> tie = {{10, 0.1, true}, {10, 0.1, false}};
  EXPECT_EQ(harness::pareto_front(tie), (std::vector<bool>{true, true}));
}

TEST(Pareto, MatchesBruteForceOnRandomPoints) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> coarse(0, 9);  // many ties in both coordinates
  for (int trial = 0; trial < 400; ++trial) {
    std::vector<TimeError> p(std::size_t(1 + trial % 40));
    // The second half of the trials mixes in unresolved points.
    for (auto& q : p) q = {double(coarse(rng)), double(coarse(rng)) * 0.1, trial < 200 || coarse(rng) < 6};
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
