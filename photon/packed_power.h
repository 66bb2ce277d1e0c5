#pragma once
// A photon's power in 4 bytes: Ward's shared-exponent RGBE, rounded to nearest.
//
// The largest channel m is stored as an 8-bit mantissa q in [128, 255] with a shared power-of-two
// exponent, the others with the same exponent. Decoding is exact (q * 2^(e-8)), so the only error
// is the rounding of the encoder: at most half a step, 2^(e-9), where m >= 2^(e-1); when m
// rounds up to 256 * 2^(e-8) the exponent grows by one, the half step is 2^(e-8) and
// m >= 255.5 * 2^(e-8). Hence
//   |decoded - c| <= max(r, g, b) / 255.5 for every channel (0.39 %), and
//   a colour whose channels are equal and whose mantissa needs at most 8 bits (1, 0.5, 0.75,
//   any power of two) is stored exactly.
// Photons of equal power (the paper's emission) all carry the same rounding error, so a
// density estimate made of them is biased by the same factor, under 0.4 % and known exactly:
// decode(encode(c)) / c. Tests: tests/photon_record_test.cpp.

#include "vec.h"

#include <array>
#include <cstdint>

namespace photon {

/// Shared-exponent power: bytes 0..2 the mantissas of r, g, b, byte 3 the exponent e + 136
/// (decoded channel = mantissa * 2^(e - 8)).
using PackedPower = std::array<std::uint8_t, 4>;

/// Encodes a power (watts per channel). Negative and NaN channels are stored as 0; a colour
/// whose largest channel is below 2^-137 W is stored as black; channels above 255 * 2^111 W
/// (6.6e35, +inf included) saturate there.
PackedPower pack_power(const Color& power);

/// Decodes pack_power's bytes (exact: every decoded channel is q * 2^(e-8)).
Color unpack_power(const PackedPower& p);

/// Worst error of pack_power on any channel, relative to the largest channel: 1/255.5.
inline constexpr float kPowerRelativeError = 1.0f / 255.5f;

}  // namespace photon
