#pragma once
// Rendering under Eric Haines' SPD test rules, so that ray counts compare with published ones.
//
// The rules (SPD README, "Testing Procedures"):
//   - rays at pixel corners: a W x H image shoots (W+1) x (H+1) eye rays, and each pixel is the
//     mean of its four corners;
//   - maximum tree depth 5, the eye ray being depth 1, with no adaptive cutoff;
//   - every hit on a reflective (Ks > 0) or transmitting surface spawns a reflection ray;
//   - a transmitting surface also spawns a refraction ray (Snell's law) unless total internal
//     reflection occurs;
//   - no shadow ray where the surface normal faces away from the light (transmitters too), and
//     none when the background is hit;
//   - opaque primitives are one-sided: their normal is never turned towards the ray, so a back
//     face is lit only from behind. Transmitters are two-sided: the normal faces the ray.
// Shading is the NFF model of nff_shading.h with SPD light intensities and no falloff; shadow
// rays stop at any primitive. Eye rays start at the camera's hither distance.

#include "render.h"

namespace tracer {

/// Maximum ray-tree depth of the SPD rules; the eye ray has depth 1.
inline constexpr int kSpdMaxDepth = 5;

/// Renders `scene` through the built structure `accel` under the SPD test rules: the
/// integrator row of tracer::spd_integrator() (render.h), rendered through tracer::render. The
/// image holds the window's pixels; RenderResult::rays counts eye rays at pixel corners.

}  // namespace tracer
