#include "sweep_measure.h"

#include "integrators.h"

#include "tracer/image.h"
#include "tracer/render.h"

#include <chrono>
#include <new>
#include <string>

namespace bench {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// One render of `scene` with the sweep's integrator.
tracer::RenderResult render_with(const tracer::Scene& scene, const accel::AnyAccel& built,
                                 const MeasureOptions& options, int width, int height, bool counting) {
  tracer::RenderOptions o;
  o.threads = options.threads;
  o.count_traversal = counting;
  o.width = width;
  o.height = height;
  return tracer::render(scene, built, o, integrator_named(options.integrator, "integrator"),
                        options.integrator_params);
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

}  // namespace

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

Measurement measure(const tracer::Scene& scene, std::span<const accel::Aabb> boxes,
                    const std::string& structure, const nlohmann::json& params,
                    const MeasureOptions& options, const std::optional<Reference>& reference) {
  Measurement m;
  accel::AnyAccel built;
  const auto t_build = Clock::now();
  try {
    built = accel::make_accel(structure, params, boxes, options.limits);
  } catch (const std::bad_alloc&) {
    m.spent_build_s = seconds_since(t_build);
    m.status = RowStatus::Failed;
    m.reason = structure + ": out of memory while building";
    return m;
  } catch (const std::exception& e) {
    m.spent_build_s = seconds_since(t_build);
    m.status = RowStatus::Failed;
    m.reason = e.what();
    return m;
  }
  m.spent_build_s = seconds_since(t_build);
  m.build_ms = m.spent_build_s * 1e3;
  m.built = true;
  m.params = accel::params_of(built);
  m.built_name = accel::name_of(built);
  m.build_stats = accel::stats_of(built);

  // One timed call of the renderer; the hash of every image must agree with the first.
  std::optional<tracer::Image> image;  // kept for the inspector
  auto render_once = [&](bool counting) -> std::optional<double> {
    const auto t0 = Clock::now();
    tracer::RenderResult r = render_with(scene, built, options, options.width, options.height, counting);
    const double s = seconds_since(t0);
    m.spent_trace_s += s;
    const std::uint64_t h = r.image.content_hash();
    if (counting) {
      m.image_hash = h;
      m.traversal = r.traversal;
      m.rays = r.rays;
      if (options.inspect) image = std::move(r.image);
    } else if (h != m.image_hash) {
      m.status = RowStatus::Error;
      m.reason = "image hash " + tracer::hash_hex(h) + " of a timed render differs from its counting pass's " +
                 tracer::hash_hex(m.image_hash) + " (nondeterministic render)";
      return std::nullopt;
    }
    return s * 1e3;
  };

  try {
    if (options.validate_width > 0) {
      // The check against naive at the validation resolution, untimed.
      const auto t0 = Clock::now();
      const tracer::RenderResult r =
          render_with(scene, built, options, options.validate_width, options.validate_height, false);
      m.spent_trace_s += seconds_since(t0);
      m.validation = Validation{options.validate_width, options.validate_height, r.image.content_hash(), r.rays};
      const std::string at =
          " at the validation resolution " + std::to_string(options.validate_width) + "x" +
          std::to_string(options.validate_height);
      if (reference) {
        if (std::string why = mismatch(m.validation->image_hash, m.validation->rays, *reference, at); !why.empty()) {
          m.status = RowStatus::Error;
          m.reason = why;
          return m;
        }
      }
    }
    render_once(true);
    if (reference && options.validate_width <= 0) {
      if (std::string why = mismatch(m.image_hash, m.rays, *reference, ""); !why.empty()) {
        m.status = RowStatus::Error;
        m.reason = why;
        return m;
      }
    }
    for (int i = 0; i < options.warmup; ++i)
      if (!render_once(false)) return m;
    std::vector<double> samples;
    for (int i = 0; i < options.repetitions; ++i) {
      const auto ms = render_once(false);
      if (!ms) return m;
      samples.push_back(*ms);
    }
    m.render_ms = summarize(samples);
    if (options.inspect) options.inspect(scene, built, options, *image, m);
  } catch (const std::bad_alloc&) {
    m.status = RowStatus::Failed;
    m.reason = structure + ": out of memory while rendering";
  } catch (const std::exception& e) {
    m.status = RowStatus::Failed;
    m.reason = std::string("render: ") + e.what();
  }
  return m;
}

}  // namespace bench
