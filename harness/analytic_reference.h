#pragma once
// References in closed form, for scenes that have one (docs/accuracy.md, "Analytic references").
//
// The diffuse furnace: point lights of total power Phi at the centre of a closed sphere of radius
// R whose inside is Lambertian with albedo rho, seen from inside. Every wall point receives the
// direct irradiance Phi / (4 pi R^2), and by symmetry every bounce spreads the reflected light
// evenly again: a uniform irradiance E = Phi / (4 pi R^2) (1 + rho + rho^2 + ...) and radiance
//   L = rho E / pi = rho Phi / (4 pi^2 R^2 (1 - rho))
// everywhere, per colour channel. An integrator that converges to the full light transport
// (ppm, and the photon integrator as its knobs tighten) converges to it; Whitted's depth-limited
// recursion stops at the first diffuse bounce and does not.

#include "tracer/image.h"
#include "tracer/scene.h"

#include <optional>

namespace harness {

/// The furnace's uniform radiance when `scene` is one: exactly one sphere and no other
/// primitive or plane; its material diffuse without highlight, albedo below 1 in every channel;
/// every light at the sphere's centre; the camera strictly inside. Otherwise nothing.
std::optional<tracer::Color> furnace_radiance(const tracer::Scene& scene);

/// The image of uniform radiance `radiance`, width x height.
tracer::Image uniform_image(const tracer::Color& radiance, int width, int height);

}  // namespace harness
