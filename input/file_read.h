#pragma once
// Reading a whole file with a size limit: only regular files, checked before a byte is read, and
// never more than the limit even when the size changes under us (or /proc reports 0).

#include "error.h"

#include <cstdint>
#include <string>
#include <string_view>

namespace input {

/// Size limits per kind of input, bytes (documented in docs/scene-format.md and docs/sweeps.md).
inline constexpr std::uint64_t kMaxSceneFileBytes = std::uint64_t(256) << 20;  ///< .json and .nff scenes: 256 MiB.
inline constexpr std::uint64_t kMaxSweepFileBytes = std::uint64_t(16) << 20;   ///< Sweep definitions: 16 MiB.
inline constexpr std::uint64_t kMaxResultsFileBytes = std::uint64_t(256) << 20;  ///< Results and JSON Lines files: 256 MiB.

/// Reads all of `path`. Throws InputError, whose what() starts with `path`, when it is not a
/// regular file (a directory, a device such as /dev/zero, a FIFO, a socket), cannot be opened or
/// read, or holds more than `max_bytes`; `what` names the kind of file in that message, e.g.
/// "big.json: 300 MiB is over the 256 MiB limit for scene files".
std::string read_file(const std::string& path, std::uint64_t max_bytes, std::string_view what);

/// "512 MiB", "3.2 GiB", "100 B": a byte count for messages.
std::string byte_text(std::uint64_t bytes);

}  // namespace input
