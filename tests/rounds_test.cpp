// harness/rounds.h: interleaved rounds visit every active contender once, alternating direction;
// a contender that fails is dropped; a stopped round leaves no samples; samples pair by round.

#include "harness/rounds.h"

#include <gtest/gtest.h>

#include <vector>

namespace {

TEST(Rounds, SerpentineOrder) {
  EXPECT_EQ(harness::round_order(3, 0), (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(harness::round_order(3, 1), (std::vector<std::size_t>{2, 1, 0}));
  EXPECT_EQ(harness::round_order(3, 2), (std::vector<std::size_t>{0, 1, 2}));
}

TEST(Rounds, EveryActiveContenderOncePerRoundPairedByRound) {
  harness::Rounds rounds(3);
  std::vector<std::size_t> visits;
  double clock = 0.0;
  const auto time = [&](std::size_t i) -> std::optional<harness::Sample> {
    visits.push_back(i);
    clock += 1.0;
    if (i == 2 && clock > 3.0) return std::nullopt;  // contender 2 fails in round 2
    return harness::Sample{clock, clock / 2.0};
  };
  ASSERT_TRUE(rounds.run({0, 1, 2}, time));
  ASSERT_TRUE(rounds.run({0, 1, 2}, time));
  ASSERT_TRUE(rounds.run({0, 1}, time));
  EXPECT_EQ(visits, (std::vector<std::size_t>{0, 1, 2, 2, 1, 0, 0, 1}));
  EXPECT_EQ(rounds.count(), 3u);
  EXPECT_EQ(rounds.samples(0).size(), 3u);
  EXPECT_EQ(rounds.samples(2).size(), 1u);  // its failed render left no sample
  EXPECT_EQ(harness::wall_times(rounds.samples(1)), (std::vector<double>{2.0, 5.0, 8.0}));
  EXPECT_EQ(harness::cpu_times(rounds.samples(1)), (std::vector<double>{1.0, 2.5, 4.0}));
  const auto [a, b] = rounds.paired_wall(0, 2);
  EXPECT_EQ(a, (std::vector<double>{1.0}));  // only round 1 has both
  EXPECT_EQ(b, (std::vector<double>{3.0}));
}

TEST(Rounds, AStoppedRoundLeavesNoSamples) {
  harness::Rounds rounds(2);
  int calls = 0;
  const auto time = [&](std::size_t) -> std::optional<harness::Sample> { return harness::Sample{1.0, 1.0}; };
  EXPECT_FALSE(rounds.run({0, 1}, time, [&] { return ++calls > 1; }));
  EXPECT_EQ(rounds.count(), 0u);
  EXPECT_TRUE(rounds.samples(0).empty());
}

}  // namespace
