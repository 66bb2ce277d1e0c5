#pragma once
// One results row: a configuration with what was measured, as the results schema describes it.

#include "harness/sweep_definition.h"
#include "harness/sweep_measure.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace harness {

/// The row of a measured configuration. Speedup and naive's figures come from `reference`
/// (naive on the same scene, timed in the same interleaved rounds); they are absent when it is,
/// and naive's time is absent while it is 0 (rows that were never timed). An ok row also carries
/// cpu_ms, render_ms_ci, speedup_ci, noisy and remeasured. With a validation
/// resolution in `options`, naive's figures go into "validated_at" and the row has no speedup
/// but a "no_speedup_reason".
nlohmann::json make_row(const SweepConfig& config, const SceneSpec& scene, std::uint64_t primitives,
                        const MeasureOptions& options, const Measurement& m,
                        const std::optional<Reference>& reference);

/// The row of a configuration that could not be measured at all (its scene failed to load).
nlohmann::json make_failed_row(const SweepConfig& config, const SceneSpec& scene,
                               const MeasureOptions& options, const std::string& reason);

}  // namespace harness
