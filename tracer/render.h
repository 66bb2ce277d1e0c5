#pragma once
// The render entry point: one scene, one built structure, one integrator chosen by the caller.
//
// An integrator (Whitted, SPD, photon mapping, ...) is one row of type Integrator: a name, its
// knobs and its render function. integrators/ keeps the one table of them; the tracer knows only its
// own. Each integrator is a template on the intersector, rendered through the one tile-parallel
// loop of render_frame.h, so every structure's loop is compiled on its own and the image and the
// statistics are bit-identical at any thread count.

#include "image.h"
#include "parallel.h"
#include "ray_counts.h"
#include "scalar.h"
#include "scene.h"

#include "accel/accel.h"
#include "knobs/knob_table.h"

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tracer {

/// A rectangle of pixels [x0, x1) x [y0, y1) of the full image.
struct PixelWindow {
  int x0 = 0;   ///< First column, pixels.
  int y0 = 0;   ///< First row, pixels (0 = top).
  int x1 = -1;  ///< One past the last column, pixels; < 0: the image width.
  int y1 = -1;  ///< One past the last row, pixels; < 0: the image height.
};

struct RenderOptions {
  int threads = 0;               ///< Worker threads; 0 = every hardware thread.
  bool count_traversal = false;  ///< Gather TraversalCounters (slower; never for timing).
  int width = 0;                 ///< Image width, pixels; 0 = the scene camera's.
  int height = 0;                ///< Image height, pixels; 0 = the scene camera's.
  PixelWindow window;            ///< Part of the image to render; default: all of it.
  /// Memory budget of what an integrator builds per render (photon maps); default 25% of RAM.
  accel::BuildLimits limits;
  /// The ray/triangle routine; each integrator sets it from its `triangle` knob.
  TriangleTest triangle_test = TriangleTest::Watertight;
  /// Stages (Integrator::stage_knob: ppm's passes) after which a progressive integrator also
  /// keeps its image, in RenderResult::checkpoints; stages not below the render's own count are
  /// ignored. Each is bit-identical to a render stopped there.
  std::vector<int> checkpoints;
};

struct RenderResult {
  Image image;                         ///< Linear RGB radiance per pixel of the window.
  RayCounts rays;                      ///< Rays traced, by kind.
  accel::TraversalCounters traversal;  ///< Summed over all rays; zero unless counted.
  /// Wall-clock time of the whole render, milliseconds: the integrator's preparation (photon
  /// tracing, map building) and the tile loop.
  double render_ms = 0;
  /// The integrator's own statistics (photon maps, phase times, ...); empty for Whitted and SPD.
  nlohmann::json stats = nlohmann::json::object();
  /// A progressive integrator's images at RenderOptions::checkpoints, by stage, fewest first.
  std::vector<std::pair<int, Image>> checkpoints;
};

/// One integrator: a row of the integrator table (integrators/integrators.h).
struct Integrator {
  std::string_view name;         ///< Its name in --integrator, scene JSON and results rows.
  std::string_view description;  ///< One line for --help and the docs.
  /// Its knob table (knobs/knob_table.h): what --param, scene files, sweeps, fronts and the docs
  /// know of its knobs.
  const knobs::AnyKnobTable& (*knob_table)();
  /// Renders with knobs already completed by `params`. Called through tracer::render only.
  RenderResult (*render)(const Scene& scene, const accel::AnyAccel& accel,
                         const RenderOptions& options, const nlohmann::json& params);
  /// Console lines (each ending in a newline) about a render's RenderResult::stats; nullptr when
  /// the integrator keeps none.
  std::string (*summary)(const nlohmann::json& stats) = nullptr;
  /// Checks completed knobs against the scene and the options before any work is done (the
  /// photon maps' memory against options.limits); throws like `params`. nullptr: nothing to check.
  void (*check)(const Scene& scene, const RenderOptions& options,
                const nlohmann::json& params) = nullptr;
  /// The knobs at which this integrator renders the reference for another integrator's fronts
  /// (a JSON object; "" when it makes none): see knobs::Front::reference_integrator.
  const char* reference_for_others = "";
  /// For a progressive integrator whose error is not all noise (ppm: the blur its shrinking
  /// radius leaves is a bias): the knob counting its stages ("passes"). Its renders return
  /// earlier stages' images on request (RenderOptions::checkpoints), from which a reference
  /// estimates its own bias (harness/reference_floor.h). nullptr: not progressive.
  const char* stage_knob = nullptr;
  /// The order p of such an integrator's bias, which falls as stages^-p at the knobs given
  /// (ppm: 1 - alpha).
  double (*bias_order)(const nlohmann::json& params) = nullptr;

  /// Every knob with its default filled in, from the given ones (a JSON object, possibly empty).
  /// Throws knobs::ConfigError, one line naming the knob, on an unknown or bad knob.
  nlohmann::json params(const nlohmann::json& given) const { return knob_table().complete(given); }
};

/// Renders `scene` through `accel`, which must have been built over
/// scene.geometry.primitive_bounds(), with `integrator` and its knobs `params` (a JSON object;
/// missing knobs take their defaults). Throws std::invalid_argument on bad options, and
/// knobs::ConfigError on bad knobs or a passed memory budget; an
/// exception in a worker thread stops the render and is rethrown here.
RenderResult render(const Scene& scene, const accel::AnyAccel& accel, const RenderOptions& options,
                    const Integrator& integrator,
                    const nlohmann::json& params = nlohmann::json::object());

/// Whitted ray tracing (tracer/whitted.h): samples_per_pixel jittered camera rays per pixel;
/// knobs max_depth, min_weight, spp and seed (tracer/whitted_params.h).
const Integrator& whitted_integrator();

/// Eric Haines' SPD test rules (tracer/spd_render.h): rays at pixel corners, tree depth 5.
const Integrator& spd_integrator();

/// Sub-pixel offset in [0, 1)^2 of sample `s` of `spp` in pixel (x, y): one sample in each stratum
/// of a rows x (spp / rows) grid (rows: the largest divisor of spp not above sqrt(spp); square
/// spp: the sqrt(spp) x sqrt(spp) grid), jittered by a hash of (x, y, s), so it is the same on
/// every run and thread and the samples are uniform over the pixel. A single sample sits at the
/// pixel centre. Another `seed` gives another, independent jitter (seed 0: the pattern of every
/// render made before seeds existed).
void sample_offset(int x, int y, int s, int spp, float& jx, float& jy, std::uint64_t seed = 0);

}  // namespace tracer
