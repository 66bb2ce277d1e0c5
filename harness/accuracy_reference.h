#pragma once
// References for speed/accuracy fronts: the image a knob's error is measured against, made by
// an independent, converged render, with an estimate of its own error (the error floor), and
// cached on disk keyed by everything that decides its pixels (docs/accuracy.md).

#include "harness/front_metric.h"
#include "harness/reference_floor.h"

#include "accel/accel.h"
#include "tracer/image.h"
#include "tracer/image_error.h"
#include "tracer/scene.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace harness {

/// Version of the reference recipe and cache format; raise it when either changes so that older
/// cached references are not used.
inline constexpr int kReferenceVersion = 3;

/// The seeds of a stochastic reference's two independent halves.
inline constexpr std::uint64_t kReferenceSeedA = 0x5eed0001;
inline constexpr std::uint64_t kReferenceSeedB = 0x5eed0002;

/// Everything that decides a reference's pixels besides the scene.
struct ReferenceSpec {
  std::string integrator;  ///< Integrator of the reference render.
  nlohmann::json params = nlohmann::json::object();  ///< Its knobs (the halves add "seed").
  bool stochastic = false;  ///< Two halves with independent seeds, the reference their mean.
  /// Knobs of the weaker check render (empty: none) whose difference from the reference
  /// estimates the reference's truncation error (Whitted's depth 48 against 64).
  nlohmann::json check = nlohmann::json::object();
  /// The integrator's stage knob when it is progressive (ppm: "passes"; tracer::Integrator::
  /// stage_knob), else empty: then the halves' stages estimate its bias (reference_floor.h).
  std::string stage_knob;
  double bias_order = 0.0;  ///< Order p of a progressive reference's bias (stages^-p).
  ReferenceEstimator estimator = ReferenceEstimator::Plain;  ///< How its stages combine.
  int width = 0;   ///< Image width, pixels (the front's resolution).
  int height = 0;  ///< Image height, pixels.
};

nlohmann::json to_json(const ReferenceSpec& s);

/// The reference's own error, estimated when it is made.
struct ReferenceFloor {
  double noise_rmse = 0.0;       ///< RMSE of the halves' mean from its expectation: RMSE(A, B)/2.
  double truncation_rmse = 0.0;  ///< RMSE between the reference and the check render: what
                                 ///< the halves cannot see (Whitted's truncation).
  /// A progressive reference's bias, RMSE: the 95% upper bound of its estimate from the stages
  /// (reference_floor.h), which the floor uses; 0 otherwise.
  double bias_rmse = 0.0;
  double bias_rmse_estimate = 0.0;  ///< The estimate itself (<= bias_rmse).
  /// The order p of N^-p the bias bound used (reference_floor.h): ppm's 1/3, or lower where the
  /// stages showed a slower fall; 0 for references without stages.
  double bias_order = 0.0;
  double rmse = 0.0;             ///< The floor in RMSE: sqrt(noise^2 + truncation^2 + bias^2).
  double rel_mse = 0.0;          ///< The floor in relative MSE (same epsilon as the fronts).
  double epsilon = tracer::kRelMseEpsilon;  ///< That epsilon.
};

nlohmann::json to_json(const ReferenceFloor& f);

/// A reference ready to compare against.
struct AccuracyReference {
  std::string key;              ///< Cache key: 16 hex digits.
  ReferenceSpec spec;           ///< How it was made.
  tracer::Image image;          ///< The reference image (the halves' mean when stochastic).
  ReferenceFloor floor;         ///< Its own error.
  nlohmann::json info;          ///< Spec, floor, render time, ray counts, when and by what made.
  bool from_cache = false;      ///< Read from the cache rather than rendered now.
  double render_s = 0.0;        ///< Wall time spent rendering it now, s (0 from the cache).
  /// Under a stopping rule (ReferenceOptions::floor_target): the target, the levels tried and
  /// what stopped them ("floor", "time_limit" or "stage_limit"); null otherwise.
  nlohmann::json stopping;
  /// The closed form it is, when the scene has one ("furnace": harness/analytic_reference.h);
  /// empty for a rendered reference.
  std::string analytic;
};

/// How to obtain references.
struct ReferenceOptions {
  std::string cache_dir;  ///< Directory of cached references; "" = no cache.
  bool refresh = false;   ///< Render even when cached (and overwrite the cache).
  int threads = 0;        ///< Render threads; 0 = all cores (images are identical at any count).
  double epsilon = tracer::kRelMseEpsilon;  ///< Epsilon of the relative-MSE floor.
  /// Check the structure against naive with the reference's knobs at this resolution before
  /// rendering a reference (0 = no check).
  int validate_width = 0;
  int validate_height = 0;  ///< Height of that check, pixels.
  bool progress = true;     ///< Lines on stderr while rendering.
  /// The stopping rule of progressive references: > 0 renders level after level, each with
  /// kStageRatio times the stages of the last, until the floor (in floor_metric) is at most this,
  /// or the next level would take the rendering past time_limit_s. 0: the recipe's stages only.
  double floor_target = 0.0;
  FrontMetric floor_metric = FrontMetric::Rmse;  ///< Metric of floor_target.
  double time_limit_s = 3600.0;  ///< Rendering time of all of one reference's levels, s.
};

/// The cache key of a reference of `scene`: FNV-1a 64 over the canonical JSON of the recipe
/// version, the whole scene (tracer::scene_to_json), the spec and the epsilon of its
/// relative-MSE floor.
std::string reference_key(const tracer::Scene& scene, const ReferenceSpec& spec,
                          double epsilon = tracer::kRelMseEpsilon);

/// The default cache directory: $XDG_CACHE_HOME/accelbench/references, else
/// $HOME/.cache/accelbench/references, else ".accelbench-cache/references".
std::string default_reference_cache();

/// The reference of `scene` (for which `built` was built over its primitive bounds) as `spec`
/// says: from the cache when it holds it (and options.refresh is off), else rendered, checked
/// and stored. A progressive spec under a stopping rule (options.floor_target) goes through its
/// levels, each cached on its own, and returns the last. Throws std::runtime_error with one line when the structure disagrees with naive,
/// the render fails, or the cache cannot be written.
AccuracyReference obtain_reference(const tracer::Scene& scene, const accel::AnyAccel& built,
                           const ReferenceSpec& spec, const ReferenceOptions& options);

}  // namespace harness
