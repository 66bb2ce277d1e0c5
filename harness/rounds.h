#pragma once
// Interleaved timing: every contender (a configuration of one scene, naive included) is timed
// once per round, and rounds repeat, so that a shared machine's drift reaches every contender
// alike instead of deciding which one looks fast. Samples stay labelled by round, so that two
// contenders' samples can be paired (harness/bootstrap.h).

#include <cstddef>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

namespace harness {

/// One timed render.
struct Sample {
  double wall_ms = 0.0;  ///< Wall-clock time, ms.
  double cpu_ms = 0.0;   ///< CPU time of the render's threads, ms (not counting time spent descheduled).
};

/// The order in which round `round` visits `n` contenders: forward in even rounds, backward in
/// odd ones, so that a drift that is linear over a round reaches every contender equally over
/// two rounds.
std::vector<std::size_t> round_order(std::size_t n, int round);

/// Samples of contenders timed in interleaved rounds.
class Rounds {
 public:
  /// Rounds over `contenders` contenders, numbered 0 .. contenders-1.
  explicit Rounds(std::size_t contenders) : n_(contenders) {}

  /// Times every contender in `active` once (round_order over them). `time(i)` returns the
  /// sample, or nullopt to drop i (its earlier samples stay). When `stop()` turns true before the
  /// round is complete, the round's samples are discarded and run returns false.
  bool run(const std::vector<std::size_t>& active, const std::function<std::optional<Sample>(std::size_t)>& time,
           const std::function<bool()>& stop = [] { return false; });

  /// Completed rounds.
  std::size_t count() const { return rounds_.size(); }

  /// Contender i's samples in round order.
  std::vector<Sample> samples(std::size_t i) const;

  /// Wall times of i and of j over the rounds in which both were timed, in round order.
  std::pair<std::vector<double>, std::vector<double>> paired_wall(std::size_t i, std::size_t j) const;

 private:
  std::size_t n_;
  std::vector<std::vector<std::optional<Sample>>> rounds_;  ///< [round][contender]
};

/// Wall times of samples, in order.
std::vector<double> wall_times(const std::vector<Sample>& samples);
/// CPU times of samples, in order.
std::vector<double> cpu_times(const std::vector<Sample>& samples);

}  // namespace harness
