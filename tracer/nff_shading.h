#pragma once
// Local shading of the NFF/SPD surface model, for every integrator that meets MaterialType::Nff.
//
// NFF's `f r g b Kd Ks Shine T ior`: a diffuse term Kd * colour, a Phong highlight of weight Ks
// and exponent Shine, a mirror reflection weighted by Ks and a refraction weighted by T. The
// recursion (reflected and refracted rays) belongs to the integrator; this file gives the terms.
// Light intensities follow the SPD README: each of n lights, and the ambient term, has the
// relative intensity sqrt(n) / (2 n), with no falloff.

#include "scene.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace tracer {

/// A material in NFF terms.
struct NffSurface {
  Color color{1.0f};          ///< Surface colour, linear RGB in [0, 1].
  float kd = 1.0f;            ///< Diffuse coefficient.
  float ks = 0.0f;            ///< Reflection coefficient and highlight weight.
  float shine = 1.0f;         ///< Phong exponent of the highlight.
  float transmittance = 0.0f; ///< Weight of the refracted ray; > 0 makes the surface two-sided.
  float ior = 1.0f;           ///< Index of refraction inside the surface (used when transmitting).
};

/// The NFF reading of any material: Nff is exact; Diffuse keeps its albedo (kd 1, no mirror);
/// Mirror becomes ks 1 in its reflectance colour; Dielectric becomes ks 0.1, T 0.9 at its ior.
inline NffSurface nff_surface(const Material& m) {
  NffSurface s;
  switch (m.type) {
    case MaterialType::Nff:
      s = {m.albedo, m.kd, m.ks, m.shininess, m.transmittance, m.ior};
      break;
    case MaterialType::Diffuse:
      s = {m.albedo, 1.0f, 0.0f, m.shininess, 0.0f, 1.0f};
      break;
    case MaterialType::Mirror:
      s = {m.reflectance, 0.0f, 1.0f, m.shininess, 0.0f, 1.0f};
      break;
    case MaterialType::Dielectric:
      s = {Color(1.0f), 0.0f, 0.1f, m.shininess, 0.9f, m.ior};
      break;
  }
  return s;
}

/// SPD relative intensity of each of `light_count` lights and of the ambient term:
/// sqrt(n) / (2 n) = 1 / (2 sqrt(n)); 0.5 when there are no lights.
inline float spd_light_intensity(std::size_t light_count) {
  return 0.5f / std::sqrt(float(std::max<std::size_t>(light_count, 1)));
}

/// Ambient term: Kd * colour * intensity.
inline Color nff_ambient(const NffSurface& s, float intensity) { return s.kd * intensity * s.color; }

/// Light arriving from one unoccluded light: Kd colour (n.l) + Ks (r.l)^Shine, times `light`.
/// `n` is the unit shading normal on the lit side, `to_eye` and `to_light` unit vectors from the
/// point; r is to_eye mirrored about n. Zero when n.l <= 0.
inline Color nff_direct(const NffSurface& s, const Vec3& n, const Vec3& to_eye,
                        const Vec3& to_light, const Color& light) {
  const float cos_l = glm::dot(n, to_light);
  if (!(cos_l > 0.0f)) return Color(0.0f);
  Color out = s.kd * cos_l * s.color;
  if (s.ks > 0.0f) {
    const Vec3 r = 2.0f * glm::dot(n, to_eye) * n - to_eye;
    const float cos_r = glm::dot(r, to_light);
    if (cos_r > 0.0f) out += Color(s.ks * std::pow(cos_r, s.shine));
  }
  return out * light;
}

}  // namespace tracer
