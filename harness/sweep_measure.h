#pragma once
// Measures one structure with one set of knobs on one scene: a timed build, an untimed counting
// pass that also yields the image hash, then warm-ups and timed renders.

#include "harness/sweep_definition.h"
#include "harness/bootstrap.h"
#include "harness/rounds.h"
#include "harness/sweep_stats.h"

#include "accel/accel.h"
#include "tracer/image.h"
#include "tracer/ray_counts.h"
#include "tracer/scene.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>
#include <span>
#include <string>

namespace harness {

/// Outcome of a configuration.
enum class RowStatus {
  Ok,      ///< Built, validated against naive, timed.
  Failed,  ///< Could not be built or rendered (memory budget, invalid knob, ...).
  Error,   ///< Built and rendered, but its image differs from naive's: never timed.
};

/// "ok", "failed" or "error".
const char* status_name(RowStatus s);

/// The knobs a sweep renders `integrator` with on `scene`: the scene's own knobs when the scene
/// chose that integrator, with `requested` (a JSON object) on top; else `requested`.
nlohmann::json scene_integrator_params(const tracer::Scene& scene, std::string_view integrator,
                                       const nlohmann::json& requested);

struct Measurement;
struct MeasureOptions;

/// Called by measure() once a configuration is validated and timed, with the scene, the built
/// structure, the options (integrator knobs included) and the rendered image. It may render more
/// (adding that time to m.spent_trace_s) and adds what it finds to m.extra. A throw makes the row
/// failed with its message.
using Inspector = std::function<void(const tracer::Scene& scene, const accel::AnyAccel& built,
                                     const MeasureOptions& options, const tracer::Image& image,
                                     Measurement& m)>;

/// How to render and time a configuration.
struct MeasureOptions {
  int width = 0;                 ///< Image width, pixels; 0 = the scene's.
  int height = 0;                ///< Image height, pixels; 0 = the scene's.
  int threads = 1;               ///< Render threads; 0 = all cores.
  int repetitions = 5;           ///< Timed renders.
  int warmup = 1;                ///< Untimed renders before them.
  accel::BuildLimits limits;     ///< Build memory budget.
  std::string integrator = "whitted";  ///< Integrator (integrators/integrators.h).
  /// The integrator's knobs (an object; empty = its defaults).
  nlohmann::json integrator_params = nlohmann::json::object();
  Inspector inspect;             ///< Optional: sees every ok configuration's image (fronts).
  int validate_width = 0;        ///< Resolution of the check against naive; 0 = the timed one.
  int validate_height = 0;       ///< Height of that check, pixels.
  bool keep_image = false;       ///< Keep the counting pass's image in Prepared::image (naive's).
};

/// The naive structure's image hash, ray counts and median render time on the same scene, same
/// run, all at one resolution: the timed one, or the validation resolution when set.
struct Reference {
  std::uint64_t image_hash = 0;   ///< Naive's image hash.
  double render_ms = 0.0;         ///< Naive's median render time, ms.
  tracer::RayCounts rays;         ///< Rays naive's render traced.
  /// Naive's image, for the structures checked within a tolerance instead of bit for bit
  /// (accel::StructureInfo::exact false: Embree's own primitives); null: they are held to the hash.
  std::shared_ptr<const tracer::Image> image;
};

/// A structure's check against naive at the validation resolution (validate_resolution).
struct Validation {
  int width = 0;                  ///< Validation width, pixels.
  int height = 0;                 ///< Validation height, pixels.
  std::uint64_t image_hash = 0;   ///< The structure's image hash at that resolution.
  tracer::RayCounts rays;         ///< The structure's ray counts at that resolution.
};

/// Everything measured for one configuration.
struct Measurement {
  RowStatus status = RowStatus::Ok;     ///< Outcome.
  std::string reason;                    ///< Why it is not ok (one line).
  bool built = false;                    ///< The structure was built.
  double build_ms = 0.0;                 ///< Build wall time (steady_clock around make_accel), ms.
  nlohmann::json params;                 ///< params_of: the exact knobs used (when built).
  std::string built_name;                ///< name_of: the structure actually built (auto picks one).
  accel::BuildStats build_stats;         ///< The structure's statistics (when built).
  std::optional<TimingStats> render_ms;  ///< Timed renders, wall clock, ms (only when ok).
  std::optional<TimingStats> cpu_ms;     ///< The same renders' CPU time (all render threads), ms.
  std::optional<Interval> render_ms_ci;  ///< 95% bootstrap interval of render_ms's median, ms.
  std::optional<double> speedup;         ///< paired_ratio of naive's times over this row's, by round.
  std::optional<Interval> speedup_ci;    ///< 95% bootstrap interval of the speedup (paired rounds).
  bool noisy = false;                    ///< The interval is wider than the sweep's noise threshold.
  int remeasured = 0;                    ///< Extra passes of rounds it was given for being noisy.
  accel::TraversalCounters traversal;    ///< From the counting pass (not timed).
  tracer::RayCounts rays;                ///< Rays traced by one render.
  std::uint64_t image_hash = 0;          ///< Image hash of the counting pass and every render.
  std::optional<Validation> validation;  ///< The separate check against naive, when one was made.
  double spent_build_s = 0.0;            ///< Wall time inside make_accel, s (overhead accounting).
  double spent_trace_s = 0.0;            ///< Wall time inside every render call, s (overhead accounting).
  /// What the inspector found (MeasureOptions::inspect), merged into the row; an object.
  nlohmann::json extra = nlohmann::json::object();
  /// The integrator's statistics (RenderResult::stats) of the counting pass and the last timed
  /// render, {"counting": ..., "timed": ...}; null when it keeps none.
  nlohmann::json integrator_stats;

  /// Rays per second at the median render time, shadow rays included (0 when not timed).
  double rays_per_s() const;
};

/// A configuration built, rendered once with counters (and checked against naive), warmed up:
/// ready for timed renders.
struct Prepared {
  Measurement measurement;             ///< Build and counting pass; status Ok means ready to time.
  accel::AnyAccel built;               ///< The structure (when measurement.built).
  std::optional<tracer::Image> image;  ///< The counting pass's image, kept for options.inspect or keep_image.
};

/// Builds `structure` with `params` on `scene`, makes the counting pass, checks it against
/// `reference` (naive's; at the validation resolution when one is set) and makes the warm-up
/// renders. Never throws for a bad knob or a failed build: those become a Failed measurement;
/// a mismatch with naive is an Error.
Prepared prepare(const tracer::Scene& scene, std::span<const accel::Aabb> boxes, const std::string& structure,
                 const nlohmann::json& params, const MeasureOptions& options, const std::optional<Reference>& reference);

/// One timed render of a prepared configuration: wall time and the CPU time of its threads
/// (CLOCK_THREAD_CPUTIME_ID with one thread, the process's CPU clock with more). Returns nullopt,
/// and makes p.m an Error, when the image differs from the counting pass's; nullopt and Failed
/// when the render throws.
std::optional<Sample> time_render(const tracer::Scene& scene, Prepared& p, const MeasureOptions& options);

/// Runs options.inspect on a timed configuration's counting image; an exception from it makes
/// p.m Failed.
void inspect(const tracer::Scene& scene, Prepared& p, const MeasureOptions& options);

/// Sets the timings of `m` from its samples: render_ms, cpu_ms, render_ms_ci.
void set_timings(Measurement& m, const std::vector<Sample>& samples);

/// Builds and measures `structure` with `params` on `scene`. Never throws for a bad knob or a
/// failed build: those become a Failed measurement. With a reference, an image or ray counts that
/// differ from naive's are an Error and are not timed. With a validation resolution in `options`,
/// that comparison is made by a render at that resolution (the reference must be naive's there)
/// and the timed renders are then made at the timed resolution. The repetitions are timed one
/// after the other (prepare, then time_render): sweeps interleave configurations instead.
Measurement measure(const tracer::Scene& scene, std::span<const accel::Aabb> boxes,
                    const std::string& structure, const nlohmann::json& params,
                    const MeasureOptions& options, const std::optional<Reference>& reference);

}  // namespace harness
