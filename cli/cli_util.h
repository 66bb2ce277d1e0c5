#pragma once
// Small pieces the subcommands share: parsing sizes from flags and describing a scene.

#include "tracer/scene.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>

namespace cli {


/// "WIDTHxHEIGHT" with both in [1, 65536]; throws std::runtime_error naming `flag`.
void parse_image_size(const std::string& text, const std::string& flag, int& width, int& height);

/// A byte count with an optional binary suffix: 1000, 64K, 512M, 2G, 1T (also KiB, MB...).
/// Throws std::runtime_error naming `flag`.
std::uint64_t parse_bytes(const std::string& text, const std::string& flag);

/// A seed: a decimal integer in [0, 2^64 - 1] (no sign, no wrap-around: "-1" is an error).
/// Throws std::runtime_error naming `flag`.
std::uint64_t parse_seed(const std::string& text, const std::string& flag);

/// Bytes the images of a width x height render take at most (two float images, a timed and a
/// counting pass, and the 8-bit copy a PNG is written from).
std::uint64_t image_bytes(int width, int height);

/// Throws std::runtime_error when an image of width x height needs more memory than
/// `budget_bytes` (the --max-memory budget; 0 = 25% of RAM), before anything is allocated. The
/// message names --max-memory when the user set the budget, else `flag` (what set the size).
void check_image_memory(int width, int height, std::uint64_t budget_bytes, const std::string& flag);

/// One line: primitives by kind, lights and materials, e.g.
/// "8000 spheres; 3 lights, 8 materials".
std::string describe_scene(const tracer::Scene& scene);

/// The scene's mesh files and what each held (--stats "meshes").
nlohmann::json mesh_stats_json(const tracer::Scene& scene);

}  // namespace cli
