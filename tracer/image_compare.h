#pragma once
// How far one image is from another: the share of visibly different pixels and the RMSE.

#include "image.h"

#include <cstddef>

namespace tracer {

/// A pixel is "off" when its largest channel difference exceeds this fraction of the brighter
/// pixel's largest channel (1%).
inline constexpr float kPixelOffFraction = 0.01f;
/// Brightness below which a pixel counts as this bright when judging "off": differences under
/// 1% of 0.01 (1e-4, far below one 8-bit step) are never counted.
inline constexpr float kPixelOffFloor = 0.01f;

struct ImageDifference {
  std::size_t pixels = 0;        ///< Pixels compared.
  std::size_t pixels_off = 0;    ///< Pixels more than 1% off (see kPixelOffFraction).
  double fraction_off = 0.0;     ///< pixels_off / pixels, in [0, 1].
  double rmse = 0.0;             ///< Root mean square difference over every channel, radiance units.
  double max_abs = 0.0;          ///< Largest absolute channel difference, radiance units.
  std::size_t non_finite = 0;    ///< Pixels of either image with a NaN or infinite channel.
};

/// A render through a structure whose own primitive routine answers (a peer such as Embree's
/// triangles: accel::StructureInfo::exact false) passes against naive's when at most this share
/// of its pixels is off: t a few ulps away moves hit points, and through glass and mirrors whole
/// paths (spheres8000's centre window through embree_points: 1.3%). A structure that loses
/// primitives is far beyond it.
inline constexpr double kPeerPixelsOffShare = 0.02;

/// The difference of two images of the same size (throws std::invalid_argument otherwise).
/// A pixel with a non-finite channel in either image counts as off.
ImageDifference compare_images(const Image& a, const Image& b);

/// Pixels of `image` with a NaN or infinite channel.
std::size_t count_non_finite(const Image& image);

}  // namespace tracer
