#pragma once
// A description of the machine and build that produced a results file.

#include <nlohmann/json.hpp>

#include <string>

namespace harness {

/// CPU model, cores, memory, OS, compiler with version, flags, build type, git commit and the
/// current UTC date, as one JSON object.
nlohmann::json machine_info();

/// The current time as ISO 8601 UTC, e.g. "2026-11-22T12:43:30Z".
std::string utc_now_iso8601();

/// The node a machine description names (its hostname); "" when it records none.
std::string node_name(const nlohmann::json& machine);

/// The machines of `machines` that differ in node, CPU model or core count, first seen first.
nlohmann::json distinct_machines(const nlohmann::json& machines);

/// When `machines` span more than one CPU model or core count: {"cpu_models": [...], "cores":
/// [...], "warning": one line}; otherwise null.
nlohmann::json mixed_hardware(const nlohmann::json& machines);

/// How every speedup in a results file is formed; written into each results file.
inline constexpr const char* kSpeedupBasis =
    "speedup = the median over the interleaved rounds this row was timed in of naive's render time "
    "in that round over the row's (naive_render_ms: naive's median over the same rounds), one run on "
    "one node (naive is timed again in every run, resumed or not); never a ratio across runs or nodes";

}  // namespace harness
