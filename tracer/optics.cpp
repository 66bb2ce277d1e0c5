#include "optics.h"

#include <algorithm>
#include <cmath>

namespace tracer {

namespace {

template <class T>
Vec3T<T> reflect_t(const Vec3T<T>& d, const Vec3T<T>& n) {
  return d - T(2) * glm::dot(d, n) * n;
}

template <class T>
bool transmitted_cos_t(T cos_i, T eta, T& cos_t) {
  const T sin2_i = std::max(T(0), T(1) - cos_i * cos_i);
  // eta * sin_i rather than eta^2 * sin^2_i: eta^2 overflows float for eta > 1.8e19, and the
  // zero test keeps eta = inf-like values away from a zero sine.
  const T sin_t = sin2_i > T(0) ? eta * std::sqrt(sin2_i) : T(0);
  if (!(sin_t < T(1))) return false;  // also catches a NaN
  cos_t = std::sqrt(std::max(T(0), T(1) - sin_t * sin_t));
  return true;
}

template <class T>
bool refract_t(const Vec3T<T>& d, const Vec3T<T>& n, T eta, Vec3T<T>& t) {
  if (eta == T(1)) {
    t = d;  // no interface: unbent, even at grazing incidence
    return true;
  }
  const T cos_i = std::clamp(-glm::dot(d, n), T(0), T(1));
  T cos_t = T(0);
  if (!transmitted_cos_t(cos_i, eta, cos_t)) return false;
  // The paper's t = eta d + (eta cos_i - cos_t) n, grouped as eta (d + cos_i n) - cos_t n: the
  // tangential part d + cos_i n is small where eta d and eta cos_i n would cancel, so a huge eta
  // at normal incidence still gives -n instead of 0.
  t = eta * (d + cos_i * n) - cos_t * n;
  return true;
}

template <class T>
T fresnel_dielectric_t(T cos_i, T eta_i, T eta_t) {
  if (eta_i == eta_t) return T(0);
  cos_i = std::min(std::abs(cos_i), T(1));
  if (cos_i == T(0)) return T(1);  // grazing: everything reflects (and 0/0 is avoided)
  T cos_t = T(0);
  if (!transmitted_cos_t(cos_i, eta_i / eta_t, cos_t)) return T(1);
  const T r_perp = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
  const T r_par = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
  return T(0.5) * (r_perp * r_perp + r_par * r_par);
}

template <class T>
InterfaceT<T> orient_t(const Vec3T<T>& d, const Vec3T<T>& n_outward, T ior_inside, T ior_outside) {
  InterfaceT<T> s;
  const T d_n = glm::dot(d, n_outward);
  s.entering = d_n <= T(0);
  s.normal = s.entering ? n_outward : -n_outward;
  s.cos_i = std::min(std::abs(d_n), T(1));
  s.eta_i = s.entering ? ior_outside : ior_inside;
  s.eta_t = s.entering ? ior_inside : ior_outside;
  return s;
}

}  // namespace

Vec3 reflect(const Vec3& d, const Vec3& n) { return reflect_t(d, n); }
glm::dvec3 reflect(const glm::dvec3& d, const glm::dvec3& n) { return reflect_t(d, n); }

bool transmitted_cos(float cos_i, float eta, float& cos_t) {
  return transmitted_cos_t(cos_i, eta, cos_t);
}
bool transmitted_cos(double cos_i, double eta, double& cos_t) {
  return transmitted_cos_t(cos_i, eta, cos_t);
}

bool refract(const Vec3& d, const Vec3& n, float eta, Vec3& t) { return refract_t(d, n, eta, t); }
bool refract(const glm::dvec3& d, const glm::dvec3& n, double eta, glm::dvec3& t) {
  return refract_t(d, n, eta, t);
}

float fresnel_dielectric(float cos_i, float eta_i, float eta_t) {
  return fresnel_dielectric_t(cos_i, eta_i, eta_t);
}
double fresnel_dielectric(double cos_i, double eta_i, double eta_t) {
  return fresnel_dielectric_t(cos_i, eta_i, eta_t);
}

Interface orient(const Vec3& d, const Vec3& n_outward, float ior_inside, float ior_outside) {
  return orient_t(d, n_outward, ior_inside, ior_outside);
}
InterfaceT<double> orient(const glm::dvec3& d, const glm::dvec3& n_outward, double ior_inside,
                          double ior_outside) {
  return orient_t(d, n_outward, ior_inside, ior_outside);
}

}  // namespace tracer
