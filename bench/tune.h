#pragma once
// Tuner: finds a structure's best max_depth x max_leaf_size on one scene by a coarse grid and
// then a refinement around the best, every point validated against naive like a sweep row.

#include "sweep_measure.h"

#include "tracer/scene.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace bench {

/// How to tune.
struct TuneOptions {
  MeasureOptions measure;                      ///< Resolution, threads, repetitions, budget.
  nlohmann::json fixed = nlohmann::json::object();  ///< Knobs held fixed (e.g. placement, split).
  std::vector<int> coarse_depths{2, 5, 8, 11, 14, 17, 20};  ///< Coarse max_depth values.
  std::vector<int> coarse_leaves{1, 2, 4, 8, 16, 32};       ///< Coarse max_leaf_size values.
  int refine_rounds = 2;                       ///< Refinements around the best, at most.
  double flat_tolerance = 0.05;                ///< "Flat region": within this fraction of the best time.
  bool progress = true;                        ///< One line per point on stderr.
};

/// One evaluated knob setting.
struct TunePoint {
  int max_depth = -1;        ///< -1 when the structure has no depth knob.
  int max_leaf_size = 0;     ///< Leaf size knob.
  int round = 0;             ///< 0 = coarse grid, 1.. = refinement round.
  Measurement m;             ///< Build, validation and timing.
};

/// What the tuner found.
struct TuneResult {
  std::string structure;             ///< Structure tuned.
  Reference naive;                   ///< Naive on the same scene and settings.
  std::vector<TunePoint> points;     ///< Every evaluated point, in evaluation order.
  std::size_t best = 0;              ///< Index of the fastest ok point.
  std::vector<std::size_t> flat;     ///< Ok points within flat_tolerance of the best, fastest first.

  /// Speedup of the best point over naive.
  double best_speedup() const { return naive.render_ms / points[best].m.render_ms->median; }
};

/// Tunes `structure` on `scene`. Throws SweepError when the structure has no leaf-size knob,
/// when naive cannot be measured, or when no point is valid.
TuneResult tune(const tracer::Scene& scene, const std::string& structure, const TuneOptions& options);

/// The result as JSON (every point, the best, the flat region).
nlohmann::json to_json(const TuneResult& r);

}  // namespace bench
