#pragma once
// Small pieces the subcommands share: parsing sizes from flags and describing a scene.

#include "tracer/scene.h"

#include <cstdint>
#include <string>

namespace bench {

/// "WIDTHxHEIGHT" with both in [1, 65536]; throws std::runtime_error naming `flag`.
void parse_resolution(const std::string& text, const std::string& flag, int& width, int& height);

/// A byte count with an optional binary suffix: 1000, 64K, 512M, 2G, 1T (also KiB, MB...).
/// Throws std::runtime_error naming `flag`.
std::uint64_t parse_bytes(const std::string& text, const std::string& flag);

/// One line: primitives by kind, lights and materials, e.g.
/// "8000 spheres; 3 lights, 8 materials".
std::string describe_scene(const tracer::Scene& scene);

}  // namespace bench
