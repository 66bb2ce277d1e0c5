#include "packed_power.h"

#include <algorithm>
#include <cmath>

namespace photon {

namespace {
// Byte 3 holds e + kExponentBias, where the largest channel m is in [2^(e-1), 2^e).
constexpr int kExponentBias = 136;

float sanitize(float c) { return c > 0.0f ? c : 0.0f; }  // NaN and negatives -> 0
}  // namespace

PackedPower pack_power(const Color& power) {
  const float r = sanitize(power.x), g = sanitize(power.y), b = sanitize(power.z);
  float m = std::max(r, std::max(g, b));
  if (std::isinf(m)) m = std::ldexp(1.0f, 120);  // saturates below
  int e = 0;
  // frexp: m = f * 2^e with f in [0.5, 1).
  std::frexp(m, &e);
  if (m == 0.0f || e + kExponentBias < 0) return {0, 0, 0, 0};
  // Mantissa of the largest channel: m * 2^(8-e) in [128, 256); rounding may reach 256, which is
  // 128 at the next exponent.
  if (std::nearbyint(std::ldexp(m, 8 - e)) >= 256.0f) ++e;
  if (e + kExponentBias > 255) e = 255 - kExponentBias;
  const auto q = [&](float c) {
    return std::uint8_t(std::min(255.0f, std::nearbyint(std::ldexp(std::min(c, m), 8 - e))));
  };
  return {q(r), q(g), q(b), std::uint8_t(e + kExponentBias)};
}

Color unpack_power(const PackedPower& p) {
  if (p[0] == 0 && p[1] == 0 && p[2] == 0) return Color(0.0f);
  const int shift = int(p[3]) - kExponentBias - 8;
  return Color(std::ldexp(float(p[0]), shift), std::ldexp(float(p[1]), shift),
               std::ldexp(float(p[2]), shift));
}

}  // namespace photon
