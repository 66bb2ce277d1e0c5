#include "packed_direction.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace photon {

namespace {
constexpr double kPi = std::numbers::pi;

DirectionTables make_tables() {
  DirectionTables t{};
  for (int i = 0; i < 256; ++i) {
    const double theta = std::min(i, 254) * kPi / 254.0, phi = i * 2.0 * kPi / 256.0;
    t.cos_theta[i] = float(std::cos(theta));
    t.sin_theta[i] = float(std::sin(theta));
    t.cos_phi[i] = float(std::cos(phi));
    t.sin_phi[i] = float(std::sin(phi));
  }
  // Exact poles and quarter turns, so axis directions decode exactly.
  t.cos_theta[0] = 1.0f, t.sin_theta[0] = 0.0f;
  t.cos_theta[127] = 0.0f, t.sin_theta[127] = 1.0f;
  t.cos_theta[254] = t.cos_theta[255] = -1.0f, t.sin_theta[254] = t.sin_theta[255] = 0.0f;
  for (int q = 0; q < 4; ++q) {
    const float c[4] = {1.0f, 0.0f, -1.0f, 0.0f}, s[4] = {0.0f, 1.0f, 0.0f, -1.0f};
    t.cos_phi[q * 64] = c[q];
    t.sin_phi[q * 64] = s[q];
  }
  return t;
}
}  // namespace

const DirectionTables kDirectionTables = make_tables();

PackedDirection pack_direction(const Vec3& d) {
  const double len = std::sqrt(double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z);
  if (!(len > 0.0) || !std::isfinite(len)) return {0, 0};
  const double z = std::clamp(double(d.z) / len, -1.0, 1.0);
  const double theta = std::acos(z);
  double phi = std::atan2(double(d.y), double(d.x));  // (-pi, pi]
  if (phi < 0.0) phi += 2.0 * kPi;
  const int ti = std::clamp(int(std::lround(theta * 254.0 / kPi)), 0, 254);
  const int pi = int(std::lround(phi * 256.0 / (2.0 * kPi))) & 255;
  return {std::uint8_t(ti), std::uint8_t(pi)};
}

}  // namespace photon
