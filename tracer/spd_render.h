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
#include "scene.h"

#include "accel/accel.h"

namespace tracer {

/// Maximum ray-tree depth of the SPD rules; the eye ray has depth 1.
inline constexpr int kSpdMaxDepth = 5;

/// A rectangle of pixels [x0, x1) x [y0, y1) of the full image.
struct PixelWindow {
  int x0 = 0;   ///< First column, pixels.
  int y0 = 0;   ///< First row, pixels (0 = top).
  int x1 = -1;  ///< One past the last column, pixels; < 0: the image width.
  int y1 = -1;  ///< One past the last row, pixels; < 0: the image height.
};

/// The Whitted render's options (threads, counting, size; 0 = the camera's NFF resolution),
/// plus a window of the image.
struct SpdOptions : RenderOptions {
  PixelWindow window;             ///< Part of the camera's image to render; default: all of it.

  SpdOptions() = default;
  explicit SpdOptions(const RenderOptions& base) : RenderOptions(base) {}
};

/// Renders `scene` through the built structure `accel` under the SPD rules. The image and the
/// counts are identical for every structure and every thread count. Throws std::invalid_argument
/// naming the option when the window or the size is out of range.
/// The image holds the window's pixels; RenderResult::rays counts eye rays at pixel corners.
RenderResult render_spd(const Scene& scene, const accel::AnyAccel& accel,
                        const SpdOptions& options = {});

}  // namespace tracer
