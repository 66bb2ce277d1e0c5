#include "harness/sweep_measure.h"

#include "integrators/integrators.h"

#include "tracer/build_accel.h"
#include "tracer/image.h"
#include "tracer/image_compare.h"
#include "tracer/intersector.h"
#include "tracer/parallel.h"
#include "tracer/render.h"

#include <time.h>

#include <chrono>
#include <new>
#include <string>

namespace harness {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double cpu_seconds(clockid_t clock) {
  timespec t{};
  clock_gettime(clock, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// One render of `scene` with the sweep's integrator.
tracer::RenderResult render_with(const tracer::Scene& scene, const accel::AnyAccel& built,
                                 const MeasureOptions& options, int width, int height, bool counting) {
  tracer::RenderOptions o;
  o.threads = options.threads;
  o.count_traversal = counting;
  o.width = width;
  o.height = height;
  o.limits = options.limits;
  return tracer::render(scene, built, o, integrators::named(options.integrator, "integrator"),
                        scene_integrator_params(scene, options.integrator, options.integrator_params));
}

/// The reason a check against naive fails, or "" when hash and ray counts agree.
std::string mismatch(std::uint64_t hash, const tracer::RayCounts& rays, const Reference& reference,
                     const std::string& where) {
  if (hash != reference.image_hash)
    return "image hash " + tracer::hash_hex(hash) + " differs from naive's " + tracer::hash_hex(reference.image_hash) +
           where;
  if (!(rays == reference.rays))
    return "ray counts " + nlohmann::json(rays).dump() + " differ from naive's " +
           nlohmann::json(reference.rays).dump() + where;
  return "";
}

/// The check of `image` against naive's: bit for bit (mismatch above) for a structure of ours,
/// within tracer::kPeerPixelsOffShare for one whose own primitive routine answers, which may
/// also trace other rays (a hit a few ulps away reflects elsewhere).
std::string check_against_naive(const std::string& structure, const tracer::Image& image,
                                const tracer::RayCounts& rays, const Reference& reference, const std::string& where) {
  const accel::StructureInfo* info = accel::find_structure(structure);
  if (!info || info->exact || !reference.image) return mismatch(image.content_hash(), rays, reference, where);
  if (image.width() != reference.image->width() || image.height() != reference.image->height())
    return "the image is not the size of naive's" + where;
  const tracer::ImageDifference d = tracer::compare_images(image, *reference.image);
  if (d.fraction_off <= tracer::kPeerPixelsOffShare) return "";
  return std::to_string(d.pixels_off) + " of " + std::to_string(d.pixels) +
         " pixels are more than 1% off naive's (a peer may have " +
         std::to_string(int(tracer::kPeerPixelsOffShare * 100.0)) + "%)" + where;
}

}  // namespace

nlohmann::json scene_integrator_params(const tracer::Scene& scene, std::string_view integrator,
                                       const nlohmann::json& requested) {
  // A scene that chose this integrator brings its knobs; the requested ones go on top of them.
  nlohmann::json knobs = requested;
  if (scene.integrator.name == integrator && scene.integrator.knobs.is_object() && !scene.integrator.knobs.empty()) {
    knobs = scene.integrator.knobs;
    for (const auto& [k, v] : requested.items()) knobs[k] = v;
  }
  return knobs;
}

const char* status_name(RowStatus s) {
  switch (s) {
    case RowStatus::Ok: return "ok";
    case RowStatus::Failed: return "failed";
    case RowStatus::Error: return "error";
  }
  return "error";
}

double Measurement::rays_per_s() const {
  if (!render_ms || render_ms->median <= 0.0) return 0.0;
  return double(rays.total()) / (render_ms->median * 1e-3);
}

Prepared prepare(const tracer::Scene& scene, std::span<const accel::Aabb> boxes, const std::string& structure,
                 const nlohmann::json& params, const MeasureOptions& options, const std::optional<Reference>& reference) {
  Prepared p;
  Measurement& m = p.measurement;
  const auto t_build = Clock::now();
  try {
    p.built = tracer::build_accel(structure, params, scene.geometry, boxes, options.limits);
  } catch (const std::bad_alloc&) {
    m.spent_build_s = seconds_since(t_build);
    m.status = RowStatus::Failed;
    m.reason = structure + ": out of memory while building";
    return p;
  } catch (const std::exception& e) {
    m.spent_build_s = seconds_since(t_build);
    m.status = RowStatus::Failed;
    m.reason = e.what();
    return p;
  }
  m.spent_build_s = seconds_since(t_build);
  m.build_ms = m.spent_build_s * 1e3;
  m.built = true;
  m.params = accel::params_of(p.built);
  m.built_name = accel::name_of(p.built);
  m.build_stats = accel::stats_of(p.built);

  try {
    if (options.validate_width > 0) {
      // The check against naive at the validation resolution, untimed.
      const auto t0 = Clock::now();
      const tracer::RenderResult r =
          render_with(scene, p.built, options, options.validate_width, options.validate_height, false);
      m.spent_trace_s += seconds_since(t0);
      m.validation = Validation{options.validate_width, options.validate_height, r.image.content_hash(), r.rays};
      const std::string at =
          " at the validation resolution " + std::to_string(options.validate_width) + "x" +
          std::to_string(options.validate_height);
      if (reference) {
        if (std::string why = check_against_naive(structure, r.image, r.rays, *reference, at); !why.empty()) {
          m.status = RowStatus::Error;
          m.reason = why;
          return p;
        }
      }
    }
    // The counting pass: traversal counters, ray counts and the hash every timed image must match.
    const auto t0 = Clock::now();
    tracer::RenderResult r = render_with(scene, p.built, options, options.width, options.height, true);
    m.spent_trace_s += seconds_since(t0);
    m.image_hash = r.image.content_hash();
    m.traversal = r.traversal;
    m.rays = r.rays;
    if (!r.stats.empty()) m.integrator_stats["counting"] = r.stats;
    if (reference && options.validate_width <= 0) {
      if (std::string why = check_against_naive(structure, r.image, m.rays, *reference, ""); !why.empty()) {
        m.status = RowStatus::Error;
        m.reason = why;
        return p;
      }
    }
    if (options.inspect || options.keep_image) p.image = std::move(r.image);
  } catch (const std::bad_alloc&) {
    m.status = RowStatus::Failed;
    m.reason = structure + ": out of memory while rendering";
    return p;
  } catch (const std::exception& e) {
    m.status = RowStatus::Failed;
    m.reason = std::string("render: ") + e.what();
    return p;
  }
  for (int i = 0; i < options.warmup; ++i)
    if (!time_render(scene, p, options)) break;
  return p;
}

std::optional<Sample> time_render(const tracer::Scene& scene, Prepared& p, const MeasureOptions& options) {
  Measurement& m = p.measurement;
  try {
    // One render thread is the calling thread (tracer::parallel_items' worker 0): its own CPU
    // clock. With more, the process's clock sums every thread's (nothing else runs meanwhile).
    const clockid_t cpu_clock = tracer::resolve_threads(options.threads) == 1 ? CLOCK_THREAD_CPUTIME_ID
                                                                               : CLOCK_PROCESS_CPUTIME_ID;
    const double cpu0 = cpu_seconds(cpu_clock);
    const auto t0 = Clock::now();
    const tracer::RenderResult r = render_with(scene, p.built, options, options.width, options.height, false);
    const double wall = seconds_since(t0);
    const double cpu = cpu_seconds(cpu_clock) - cpu0;
    m.spent_trace_s += wall;
    if (!r.stats.empty()) m.integrator_stats["timed"] = r.stats;
    const std::uint64_t h = r.image.content_hash();
    if (h != m.image_hash) {
      m.status = RowStatus::Error;
      m.reason = "image hash " + tracer::hash_hex(h) + " of a timed render differs from its counting pass's " +
                 tracer::hash_hex(m.image_hash) + " (nondeterministic render)";
      return std::nullopt;
    }
    return Sample{wall * 1e3, cpu * 1e3};
  } catch (const std::bad_alloc&) {
    m.status = RowStatus::Failed;
    m.reason = m.built_name + ": out of memory while rendering";
  } catch (const std::exception& e) {
    m.status = RowStatus::Failed;
    m.reason = std::string("render: ") + e.what();
  }
  return std::nullopt;
}

void inspect(const tracer::Scene& scene, Prepared& p, const MeasureOptions& options) {
  if (!options.inspect || !p.image) return;
  try {
    options.inspect(scene, p.built, options, *p.image, p.measurement);
  } catch (const std::exception& e) {
    p.measurement.status = RowStatus::Failed;
    p.measurement.reason = std::string("inspect: ") + e.what();
  }
}

void set_timings(Measurement& m, const std::vector<Sample>& samples) {
  if (samples.empty()) return;
  m.render_ms = summarize(wall_times(samples));
  m.cpu_ms = summarize(cpu_times(samples));
  m.render_ms_ci = median_interval(wall_times(samples));
}

Measurement measure(const tracer::Scene& scene, std::span<const accel::Aabb> boxes,
                    const std::string& structure, const nlohmann::json& params,
                    const MeasureOptions& options, const std::optional<Reference>& reference) {
  Prepared p = prepare(scene, boxes, structure, params, options, reference);
  if (p.measurement.status != RowStatus::Ok) return std::move(p.measurement);
  std::vector<Sample> samples;
  for (int i = 0; i < options.repetitions; ++i) {
    const auto s = time_render(scene, p, options);
    if (!s) return std::move(p.measurement);
    samples.push_back(*s);
  }
  set_timings(p.measurement, samples);
  inspect(scene, p, options);
  return std::move(p.measurement);
}

}  // namespace harness
