#pragma once
// Random numbers of one photon path, from (seed, stream, index) alone: a counter-based splitmix64
// stream, so photon i draws the same numbers whichever thread traces it and whatever was traced
// before it. Maps and images are then bit-identical at any thread count.

#include <cstdint>

namespace photon {

class PhotonRng {
 public:
  /// The stream of path `index` of stream `stream` (one per photon pass or gather) under `seed`.
  PhotonRng(std::uint64_t seed, std::uint64_t stream, std::uint64_t index)
      : state_(mix(mix(seed ^ 0x243f6a8885a308d3ull) ^ mix(stream + 0x13198a2e03707344ull) ^
                   mix(index + 0xa4093822299f31d0ull))) {}

  /// The next 64 random bits.
  std::uint64_t next() { return mix(state_ += 0x9e3779b97f4a7c15ull); }

  /// A uniform float in [0, 1): the top 24 bits of one draw.
  float uniform() { return float(next() >> 40) * 0x1.0p-24f; }

  /// splitmix64's finaliser: a bijection on 64 bits with full avalanche.
  static std::uint64_t mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }

 private:
  std::uint64_t state_;
};

}  // namespace photon
