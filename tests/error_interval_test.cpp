// Front points' error intervals (harness/error_interval.h): the seeds' spread widened by the
// reference's floor, linearly in RMSE and in the square roots of the relative MSE, and resolved
// only when the interval's lower end lies above the floor.

#include "harness/error_interval.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace {

using harness::ErrorInterval;
using harness::FrontMetric;
using harness::Interval;

constexpr double kInf = std::numeric_limits<double>::infinity();

ErrorInterval rmse_interval(double error, double floor) {
  return harness::error_interval(harness::seed_spread(error, {}), floor, FrontMetric::Rmse);
}

TEST(ErrorInterval, RmseAtBelowAndAboveTheFloor) {
  const double f = 0.01;
  // Exactly at the floor: the truth may be anywhere from 0 to twice the floor.
  ErrorInterval at = rmse_interval(0.01, f);
  EXPECT_DOUBLE_EQ(at.lo, 0.0);
  EXPECT_DOUBLE_EQ(at.hi, 0.02);
  EXPECT_FALSE(at.resolved);
  // Below it.
  ErrorInterval below = rmse_interval(0.004, f);
  EXPECT_DOUBLE_EQ(below.lo, 0.0);
  EXPECT_DOUBLE_EQ(below.hi, 0.014);
  EXPECT_FALSE(below.resolved);
  // Twice the floor: the lower end reaches the floor itself, still unresolved.
  ErrorInterval twice = rmse_interval(0.02, f);
  EXPECT_DOUBLE_EQ(twice.lo, 0.01);
  EXPECT_FALSE(twice.resolved);
  // Just past twice the floor: resolved.
  EXPECT_TRUE(rmse_interval(0.0201, f).resolved);
  // Far above: a narrow interval around the error.
  ErrorInterval far = rmse_interval(0.5, f);
  EXPECT_DOUBLE_EQ(far.lo, 0.49);
  EXPECT_DOUBLE_EQ(far.hi, 0.51);
  EXPECT_TRUE(far.resolved);
}

TEST(ErrorInterval, AZeroFloorResolvesEveryNonZeroError) {
  // The precision front's double reference has floor 0: float's small error is resolved, the
  // reference's own configuration (error 0) is not.
  const ErrorInterval tiny = rmse_interval(1e-5, 0.0);
  EXPECT_DOUBLE_EQ(tiny.lo, 1e-5);
  EXPECT_DOUBLE_EQ(tiny.hi, 1e-5);
  EXPECT_TRUE(tiny.resolved);
  EXPECT_FALSE(rmse_interval(0.0, 0.0).resolved);
}

TEST(ErrorInterval, RelativeMseAddsTheFloorInTheSquareRoots) {
  const double f = 1e-4;  // sqrt: 0.01
  // 4e-4 (sqrt 0.02): the lower end (0.02 - 0.01)^2 = 1e-4 is the floor: unresolved. A linear
  // rule (4e-4 - 1e-4 = 3e-4 > 1e-4) would call it resolved.
  const ErrorInterval at = harness::error_interval({4e-4, 4e-4}, f, FrontMetric::RelMse);
  EXPECT_NEAR(at.lo, 1e-4, 1e-18);
  EXPECT_NEAR(at.hi, 9e-4, 1e-18);
  EXPECT_FALSE(at.resolved);
  // 1e-2 (sqrt 0.1): [0.09^2, 0.11^2].
  const ErrorInterval far = harness::error_interval({1e-2, 1e-2}, f, FrontMetric::RelMse);
  EXPECT_NEAR(far.lo, 0.0081, 1e-15);
  EXPECT_NEAR(far.hi, 0.0121, 1e-15);
  EXPECT_TRUE(far.resolved);
  // Below the floor: from 0.
  const ErrorInterval below = harness::error_interval({5e-5, 5e-5}, f, FrontMetric::RelMse);
  EXPECT_EQ(below.lo, 0.0);
  EXPECT_FALSE(below.resolved);
}

TEST(ErrorInterval, SeedNoiseWidensTheInterval) {
  // Four seeds: their range (the bootstrap interval of the median of up to five values).
  const Interval seed = harness::seed_spread(0.1, {0.1, 0.08, 0.12, 0.09});
  EXPECT_DOUBLE_EQ(seed.lo, 0.08);
  EXPECT_DOUBLE_EQ(seed.hi, 0.12);
  const ErrorInterval e = harness::error_interval(seed, 0.04, FrontMetric::Rmse);
  EXPECT_DOUBLE_EQ(e.lo, 0.04);
  EXPECT_DOUBLE_EQ(e.hi, 0.16);
  // Without the seed noise the same error would be resolved: 0.1 - 0.04 > 0.04.
  EXPECT_FALSE(e.resolved);
  EXPECT_TRUE(rmse_interval(0.1, 0.04).resolved);
  // Many seeds: the bootstrap interval of their median, narrower than their range, and always
  // holding the measured (timed) error, which is the point drawn.
  std::vector<double> many;
  for (int i = 0; i < 40; ++i) many.push_back(0.1 + 0.001 * (i % 20));
  const Interval ci = harness::seed_spread(0.3, many);
  EXPECT_GT(ci.lo, 0.1);
  EXPECT_DOUBLE_EQ(ci.hi, 0.3);
  // One seed is no spread.
  const Interval one = harness::seed_spread(0.2, {0.2});
  EXPECT_EQ(one.lo, 0.2);
  EXPECT_EQ(one.hi, 0.2);
}

TEST(ErrorInterval, ABrokenRenderIsResolvedAndUnbounded) {
  const ErrorInterval broken = rmse_interval(kInf, 0.01);
  EXPECT_EQ(broken.lo, kInf);
  EXPECT_EQ(broken.hi, kInf);
  EXPECT_TRUE(broken.resolved);
  // A broken extra seed: no upper bound.
  const Interval seed = harness::seed_spread(0.1, {0.1, kInf, 0.09});
  EXPECT_DOUBLE_EQ(seed.lo, 0.09);
  EXPECT_EQ(seed.hi, kInf);
}

}  // namespace
