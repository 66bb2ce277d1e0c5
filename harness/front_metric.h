#pragma once
// The error metric a speed/accuracy front is drawn and tuned on (docs/accuracy.md).

namespace harness {

/// The error metric a front is drawn and tuned on.
enum class FrontMetric { Rmse, RelMse };

/// "rmse" or "rel_mse": the metric's key in a row's "error" and in a reference's "floor".
inline const char* metric_name(FrontMetric m) { return m == FrontMetric::Rmse ? "rmse" : "rel_mse"; }

}  // namespace harness
