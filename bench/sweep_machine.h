#pragma once
// A description of the machine and build that produced a results file.

#include <nlohmann/json.hpp>

#include <string>

namespace bench {

/// CPU model, cores, memory, OS, compiler with version, flags, build type, git commit and the
/// current UTC date, as one JSON object.
nlohmann::json machine_info();

/// The current time as ISO 8601 UTC, e.g. "2026-11-22T12:43:30Z".
std::string utc_now_iso8601();

}  // namespace bench
