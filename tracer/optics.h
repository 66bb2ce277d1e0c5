#pragma once
// Reflection, refraction and Fresnel reflectance at a smooth dielectric interface, after the
// formulas of "A Better Ray Tracer": t = eta i + (eta cos_i - sqrt(1 - eta^2 (1 - cos_i^2))) n,
// total internal reflection when the radicand is negative, R = (R_perp + R_par) / 2, T = 1 - R.
// Each function exists in float (the renderer) and double (the naive reference), computed by
// the same code.

#include "scalar.h"

#include "accel/geometry.h"

namespace tracer {

using accel::Vec3;

/// Mirror direction of `d` about the unit normal `n` (either side): d - 2 (d.n) n.
Vec3 reflect(const Vec3& d, const Vec3& n);
glm::dvec3 reflect(const glm::dvec3& d, const glm::dvec3& n);

/// Cosine of the transmitted angle for incidence cosine `cos_i` (>= 0) and relative index
/// eta = eta_i / eta_t; false under total internal reflection (sin_t >= 1). The radicand is
/// clamped at 0, and a zero sin_i never meets eta (so eta = 1e20 gives no inf * 0).
bool transmitted_cos(float cos_i, float eta, float& cos_t);
bool transmitted_cos(double cos_i, double eta, double& cos_t);

/// Refracted unit direction of the unit direction `d` through the unit normal `n` that faces
/// against it (d.n <= 0), with eta = eta_i / eta_t. Returns false under total internal
/// reflection and leaves `t` untouched. eta = 1 returns d itself, bit for bit.
bool refract(const Vec3& d, const Vec3& n, float eta, Vec3& t);
bool refract(const glm::dvec3& d, const glm::dvec3& n, double eta, glm::dvec3& t);

/// Unpolarised Fresnel reflectance (R_perp + R_par) / 2 for light arriving from the medium of
/// index eta_i at the cosine cos_i (its sign is ignored) into the medium of index eta_t.
/// 1 under total internal reflection, 0 when the indices are equal. T = 1 - R.
float fresnel_dielectric(float cos_i, float eta_i, float eta_t);
double fresnel_dielectric(double cos_i, double eta_i, double eta_t);

/// A ray meeting a dielectric surface, oriented by the sign of d.n, in the scalar type T.
template <class T>
struct InterfaceT {
  Vec3T<T> normal;       ///< Unit normal on the side the ray arrives from (d.normal <= 0).
  T cos_i = T(1);        ///< Cosine of the incidence angle, in [0, 1].
  T eta_i = T(1);        ///< Index of refraction of the medium the ray travels in.
  T eta_t = T(1);        ///< Index of refraction of the medium beyond the surface.
  bool entering = true;  ///< True when the ray arrives from outside (d.n_outward < 0).
};
using Interface = InterfaceT<float>;

/// Orients the surface with outward unit normal `n_outward` for the unit direction `d`: a ray
/// with d.n_outward > 0 is inside and leaves with eta = ior_inside / ior_outside.
Interface orient(const Vec3& d, const Vec3& n_outward, float ior_inside, float ior_outside = 1.0f);
InterfaceT<double> orient(const glm::dvec3& d, const glm::dvec3& n_outward, double ior_inside,
                          double ior_outside = 1.0);

}  // namespace tracer
