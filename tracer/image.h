#pragma once
// A linear float RGB image, its PNG/PFM files, and a hash of its exact contents.

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace tracer {

class Image {
 public:
  using Pixel = glm::vec3;  ///< Linear RGB radiance.

  Image() = default;
  /// A black image of width x height pixels (both >= 0).
  Image(int width, int height);

  int width() const { return width_; }    ///< Pixels.
  int height() const { return height_; }  ///< Pixels.
  /// Pixel (x, y); (0, 0) is the top-left corner. No bounds check.
  Pixel& at(int x, int y) { return pixels_[std::size_t(y) * std::size_t(width_) + std::size_t(x)]; }
  const Pixel& at(int x, int y) const {
    return pixels_[std::size_t(y) * std::size_t(width_) + std::size_t(x)];
  }
  /// Row-major pixels, top row first.
  const std::vector<Pixel>& pixels() const { return pixels_; }

  /// Mean of every channel of every pixel (in double), or 0 for an empty image.
  double mean() const;

  /// 8-bit sRGB PNG of the image scaled by 2^exposure_ev, clamped to [0, 1]. Throws
  /// std::runtime_error naming the path when the file cannot be written.
  void write_png(const std::string& path, float exposure_ev = 0.0f) const;

  /// Portable float map (little-endian "PF", rows bottom to top), the exact linear values.
  void write_pfm(const std::string& path) const;

  /// Reads a colour PFM of either byte order. Throws std::runtime_error with a one-line reason.
  static Image read_pfm(const std::string& path);

  /// FNV-1a 64 over the size and the bit patterns of every float: equal hashes mean identical
  /// images, which is how structures and thread counts are compared.
  std::uint64_t content_hash() const;

  friend bool operator==(const Image&, const Image&) = default;

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<Pixel> pixels_;
};

/// The hash as 16 lowercase hex digits, as written in statistics files.
std::string hash_hex(std::uint64_t hash);

}  // namespace tracer
