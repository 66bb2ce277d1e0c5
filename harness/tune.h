#pragma once
// Tuner: finds a structure's best max_depth x max_leaf_size on one scene by a coarse grid and a
// refinement around the best, every point validated against naive like a sweep row; then
// confirms the winner: the best candidates of the search (and naive) are timed again together,
// interleaved round by round, and a winner is named only when its interval separates it from
// every other candidate. Otherwise the candidates tie, and the tie is reported.

#include "harness/bootstrap.h"
#include "harness/rounds.h"
#include "harness/sweep_measure.h"

#include "tracer/scene.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace harness {

/// How to tune.
struct TuneOptions {
  MeasureOptions measure;                      ///< Resolution, threads, repetitions, budget.
  nlohmann::json fixed = nlohmann::json::object();  ///< Knobs held fixed (e.g. placement, split).
  std::vector<int> coarse_depths{2, 5, 8, 11, 14, 17, 20};  ///< Coarse max_depth values.
  std::vector<int> coarse_leaves{1, 2, 4, 8, 16, 32};       ///< Coarse max_leaf_size values.
  int refine_rounds = 2;                       ///< Refinements around the best, at most.
  std::size_t confirm_candidates = 6;          ///< Best points of the search timed again to confirm.
  int confirm_rounds = 0;                      ///< Interleaved rounds of the confirmation; 0 = max(9, 3 x repetitions).
  double flat_tolerance = 0.05;                ///< "Flat region": not shown slower than the best by more than this.
  bool progress = true;                        ///< One line per point on stderr.
};

/// A point's confirmation: its timings in the interleaved rounds, against the fastest candidate.
struct Confirmation {
  TimingStats render_ms;    ///< Its samples in the confirmation rounds, ms.
  Interval render_ms_ci;    ///< 95% interval of their median, ms.
  double ratio = 1.0;       ///< paired_ratio of its times over the fastest candidate's, by round.
  Interval ratio_ci;        ///< 95% bootstrap interval of that ratio.
};

/// One evaluated knob setting.
struct TunePoint {
  int max_depth = -1;        ///< -1 when the structure has no depth knob.
  int max_leaf_size = 0;     ///< Leaf size knob.
  int round = 0;             ///< 0 = coarse grid, 1.. = refinement round.
  Measurement m;             ///< The search's build, validation and timing.
  std::optional<Confirmation> confirmed;  ///< Set for the candidates that were confirmed.
};

/// What the tuner measures with: the real one builds and renders (tune()); tests give synthetic
/// timings with noise to check the decision rule.
class TuneTarget {
 public:
  virtual ~TuneTarget() = default;
  /// Naive's check: its image hash and ray counts (what every point must match). Throws
  /// SweepError when naive cannot be rendered.
  virtual Reference naive() = 0;
  /// A point of the search: built, validated against `naive`, timed `repetitions` times in a row.
  virtual Measurement search(const nlohmann::json& params) = 0;
  /// Prepares the confirmation's contenders: naive (contender 0), then `params` in order (1..).
  /// Returns false for a contender that cannot be prepared again.
  virtual std::vector<bool> prepare_confirmation(const std::vector<nlohmann::json>& params) = 0;
  /// One timed render of confirmation contender i; nullopt when it fails.
  virtual std::optional<Sample> time(std::size_t i) = 0;
};

/// What the tuner found.
struct TuneResult {
  std::string structure;             ///< Structure tuned.
  Reference naive;                   ///< Naive's check; render_ms = its median in the confirmation rounds.
  std::vector<TunePoint> points;     ///< Every evaluated point, in evaluation order.
  std::vector<std::size_t> candidates;  ///< Confirmed points, fastest confirmed median first.
  std::size_t best = 0;              ///< The fastest confirmed point (candidates.front()).
  bool separated = false;            ///< best's interval separates it from every other candidate.
  std::vector<std::size_t> tie;      ///< Candidates that cannot be told from best at 95% (best first; only best when separated).
  std::vector<std::size_t> flat;     ///< Candidates not shown slower than best by more than flat_tolerance.
  int confirm_rounds = 0;            ///< Interleaved rounds the confirmation ran.
  double best_speedup = 0.0;         ///< paired_ratio of naive's times over best's, by round.
  Interval best_speedup_ci;          ///< Its 95% bootstrap interval.
};

/// Tunes through `target` a structure with knobs `knobs` (it must have max_leaf_size). Throws
/// SweepError when no point is valid.
TuneResult tune_with(TuneTarget& target, const std::string& structure, const std::vector<std::string>& knobs,
                     const TuneOptions& options);

/// Tunes `structure` on `scene`. Throws SweepError when the structure has no leaf-size knob,
/// when naive cannot be measured, or when no point is valid.
TuneResult tune(const tracer::Scene& scene, const std::string& structure, const TuneOptions& options);

/// The result as JSON (every point, the confirmation, the winner or the tie, the flat region).
nlohmann::json to_json(const TuneResult& r);

}  // namespace harness
