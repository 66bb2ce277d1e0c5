#pragma once
// Random numbers that are the same on every platform: std::mt19937_64 is fully specified by the
// standard, but the std distributions are not, so floats are mapped from the raw bits here.

#include <cstdint>
#include <random>

namespace scenes_gen {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}

  /// Uniform float in [0, 1): the top 24 bits of one 64-bit draw.
  float uniform() { return float(engine_() >> 40) * 0x1.0p-24f; }

  /// Uniform float in [lo, hi).
  float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }

  /// Uniform integer in [0, n), n > 0 (bias below 2^-32 for the n used here).
  std::uint32_t below(std::uint32_t n) { return std::uint32_t((engine_() >> 32) * n >> 32); }

 private:
  std::mt19937_64 engine_;
};

}  // namespace scenes_gen
