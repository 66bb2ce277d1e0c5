#include "harness/sweep_row.h"

#include "input/message.h"
#include "tracer/image.h"

namespace harness {
namespace {

nlohmann::json row_head(const SweepConfig& config, const SceneSpec& scene, const MeasureOptions& options) {
  return {{"index", config.index},
          {"key", config.key},
          {"scene", scene.name},
          {"scene_family", scene.family()},
          {"structure", config.structure},
          {"integrator", options.integrator},
          {"requested", config.params},
          {"width", options.width},
          {"height", options.height},
          {"threads", options.threads},
          {"repetitions", options.repetitions},
          {"warmup", options.warmup}};
}

void add_integrator_params(nlohmann::json& row, const SweepConfig& config) {
  if (!config.integrator_params.empty()) row["integrator_params"] = config.integrator_params;
}

}  // namespace

nlohmann::json make_row(const SweepConfig& config, const SceneSpec& scene, std::uint64_t primitives,
                        const MeasureOptions& options, const Measurement& m,
                        const std::optional<Reference>& reference) {
  nlohmann::json row = row_head(config, scene, options);
  add_integrator_params(row, config);
  row["primitives"] = primitives;
  row["status"] = status_name(m.status);
  if (m.status != RowStatus::Ok) row["reason"] = input::one_line(m.reason);
  if (m.built) {
    row["built"] = m.built_name;
    row["params"] = m.params;
    row["build_ms"] = m.build_ms;
    row["build_stats"] = m.build_stats;
  }
  if (m.image_hash != 0 || m.rays.total() != 0) {
    row["image_hash"] = tracer::hash_hex(m.image_hash);
    row["traversal"] = m.traversal;
    row["rays"] = m.rays;
  }
  if (!m.integrator_stats.is_null() && !m.integrator_stats.empty())
    row["integrator_stats"] = m.integrator_stats;
  // With a validation resolution, naive was rendered and timed only there: its figures belong to
  // the validation record, and no speedup is claimed against a time taken at another resolution.
  const bool apart = options.validate_width > 0;
  if (m.validation) {
    nlohmann::json v = {{"width", m.validation->width},
                        {"height", m.validation->height},
                        {"image_hash", tracer::hash_hex(m.validation->image_hash)},
                        {"rays", m.validation->rays}};
    if (reference) {
      v["naive_image_hash"] = tracer::hash_hex(reference->image_hash);
      v["naive_rays"] = reference->rays;
      if (reference->render_ms > 0.0) v["naive_render_ms"] = reference->render_ms;  // timed (ok rows)
    }
    row["validated_at"] = v;
  }
  if (reference && !apart) {
    row["naive_image_hash"] = tracer::hash_hex(reference->image_hash);
    if (reference->render_ms > 0.0) row["naive_render_ms"] = reference->render_ms;  // timed (ok rows)
  }
  // Only a validated configuration carries speeds.
  if (m.status == RowStatus::Ok && m.render_ms) {
    row["render_ms"] = *m.render_ms;
    if (m.cpu_ms) row["cpu_ms"] = *m.cpu_ms;
    if (m.render_ms_ci) row["render_ms_ci"] = {m.render_ms_ci->lo, m.render_ms_ci->hi};
    row["noisy"] = m.noisy;
    row["remeasured"] = m.remeasured;
    row["rays_per_s"] = m.rays_per_s();
    if (apart) {
      row["no_speedup_reason"] = "naive was timed only at the validation resolution " +
                                 std::to_string(options.validate_width) + "x" +
                                 std::to_string(options.validate_height) + ", not at the timed resolution";
    } else if (reference && reference->render_ms > 0.0 && m.speedup) {
      row["speedup"] = *m.speedup;
      if (m.speedup_ci) row["speedup_ci"] = {m.speedup_ci->lo, m.speedup_ci->hi};
    }
  }
  for (const auto& [key, value] : m.extra.items()) row[key] = value;
  return row;
}

nlohmann::json make_failed_row(const SweepConfig& config, const SceneSpec& scene,
                               const MeasureOptions& options, const std::string& reason) {
  nlohmann::json row = row_head(config, scene, options);
  add_integrator_params(row, config);
  row["status"] = status_name(RowStatus::Failed);
  row["reason"] = input::one_line(reason);
  return row;
}

}  // namespace harness
