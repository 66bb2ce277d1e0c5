#include "optics.h"

#include <algorithm>
#include <cmath>

namespace tracer {

Vec3 reflect(const Vec3& d, const Vec3& n) {
  return d - 2.0f * glm::dot(d, n) * n;
}

bool transmitted_cos(float cos_i, float eta, float& cos_t) {
  const float sin2_i = std::max(0.0f, 1.0f - cos_i * cos_i);
  // eta * sin_i rather than eta^2 * sin^2_i: eta^2 overflows float for eta > 1.8e19, and the
  // zero test keeps eta = inf-like values away from a zero sine.
  const float sin_t = sin2_i > 0.0f ? eta * std::sqrt(sin2_i) : 0.0f;
  if (!(sin_t < 1.0f)) return false;  // also catches a NaN
  cos_t = std::sqrt(std::max(0.0f, 1.0f - sin_t * sin_t));
  return true;
}

bool refract(const Vec3& d, const Vec3& n, float eta, Vec3& t) {
  if (eta == 1.0f) {
    t = d;  // no interface: unbent, even at grazing incidence
    return true;
  }
  const float cos_i = std::clamp(-glm::dot(d, n), 0.0f, 1.0f);
  float cos_t = 0.0f;
  if (!transmitted_cos(cos_i, eta, cos_t)) return false;
  // The paper's t = eta d + (eta cos_i - cos_t) n, grouped as eta (d + cos_i n) - cos_t n: the
  // tangential part d + cos_i n is small where eta d and eta cos_i n would cancel, so a huge eta
  // at normal incidence still gives -n instead of 0.
  t = eta * (d + cos_i * n) - cos_t * n;
  return true;
}

float fresnel_dielectric(float cos_i, float eta_i, float eta_t) {
  if (eta_i == eta_t) return 0.0f;
  cos_i = std::min(std::abs(cos_i), 1.0f);
  if (cos_i == 0.0f) return 1.0f;  // grazing: everything reflects (and 0/0 is avoided)
  float cos_t = 0.0f;
  if (!transmitted_cos(cos_i, eta_i / eta_t, cos_t)) return 1.0f;
  const float r_perp = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
  const float r_par = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
  return 0.5f * (r_perp * r_perp + r_par * r_par);
}

Interface orient(const Vec3& d, const Vec3& n_outward, float ior_inside, float ior_outside) {
  Interface s;
  const float d_n = glm::dot(d, n_outward);
  s.entering = d_n <= 0.0f;
  s.normal = s.entering ? n_outward : -n_outward;
  s.cos_i = std::min(std::abs(d_n), 1.0f);
  s.eta_i = s.entering ? ior_outside : ior_inside;
  s.eta_t = s.entering ? ior_inside : ior_outside;
  return s;
}

}  // namespace tracer
