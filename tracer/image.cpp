#include "image.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace tracer {

Image::Image(int width, int height) : width_(width), height_(height) {
  if (width < 0 || height < 0)
    throw std::invalid_argument("image size must be >= 0, got " + std::to_string(width) + "x" +
                                std::to_string(height));
  pixels_.assign(std::size_t(width) * std::size_t(height), Pixel(0.0f));
}

double Image::mean() const {
  if (pixels_.empty()) return 0.0;
  double sum = 0.0;
  for (const Pixel& p : pixels_) sum += double(p.x) + double(p.y) + double(p.z);
  return sum / (3.0 * double(pixels_.size()));
}

namespace {

std::uint8_t to_srgb8(float linear) {
  if (!(linear > 0.0f)) return 0;  // negatives and NaN
  if (linear >= 1.0f) return 255;
  const float s =
      linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
  return std::uint8_t(std::lround(s * 255.0f));
}

float byte_swapped(float f) {
  const std::uint32_t u = std::bit_cast<std::uint32_t>(f);
  return std::bit_cast<float>((u >> 24) | ((u >> 8) & 0xff00u) | ((u << 8) & 0xff0000u) |
                              (u << 24));
}

}  // namespace

void Image::write_png(const std::string& path, float exposure_ev) const {
  if (width_ == 0 || height_ == 0)
    throw std::runtime_error("cannot write an empty image to '" + path + "'");
  // stb_image_write sizes its buffers in int: refuse images whose filtered rows pass that.
  if ((std::int64_t(width_) * 3 + 1) * std::int64_t(height_) > std::int64_t(std::numeric_limits<int>::max()))
    throw std::runtime_error("cannot write '" + path + "': " + std::to_string(width_) + "x" +
                             std::to_string(height_) + " is too large for a PNG here (write --pfm instead)");
  const float scale = std::exp2(exposure_ev);
  std::vector<std::uint8_t> bytes(pixels_.size() * 3);
  for (std::size_t i = 0; i < pixels_.size(); ++i)
    for (int c = 0; c < 3; ++c) bytes[3 * i + c] = to_srgb8(pixels_[i][c] * scale);
  if (!stbi_write_png(path.c_str(), width_, height_, 3, bytes.data(), width_ * 3))
    throw std::runtime_error("cannot write PNG '" + path + "'");
}

void Image::write_pfm(const std::string& path) const {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write PFM '" + path + "'");
  out << "PF\n" << width_ << ' ' << height_ << "\n-1.0\n";  // negative scale: little-endian
  std::vector<float> row(std::size_t(width_) * 3);
  for (int y = height_ - 1; y >= 0; --y) {
    for (int x = 0; x < width_; ++x)
      for (int c = 0; c < 3; ++c) row[3 * std::size_t(x) + c] = at(x, y)[c];
    if constexpr (std::endian::native == std::endian::big)
      for (float& f : row) f = byte_swapped(f);
    out.write(reinterpret_cast<const char*>(row.data()),
              std::streamsize(row.size() * sizeof(float)));
  }
  if (!out) throw std::runtime_error("cannot write PFM '" + path + "'");
}

Image Image::read_pfm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open PFM '" + path + "'");
  std::string magic;
  long long w = 0, h = 0;
  double scale = 0.0;
  in >> magic >> w >> h >> scale;
  if (!in || magic != "PF") throw std::runtime_error(path + ": not a colour PFM (expected 'PF')");
  if (w <= 0 || h <= 0 || w > 1 << 16 || h > 1 << 16)
    throw std::runtime_error(path + ": bad PFM size " + std::to_string(w) + "x" +
                             std::to_string(h));
  if (scale == 0.0 || !std::isfinite(scale)) throw std::runtime_error(path + ": bad PFM scale");
  in.get();  // the single whitespace byte after the header
  const bool swap = (scale < 0.0) != (std::endian::native == std::endian::little);
  Image img{int(w), int(h)};
  std::vector<float> row(std::size_t(w) * 3);
  for (long long y = h - 1; y >= 0; --y) {
    in.read(reinterpret_cast<char*>(row.data()), std::streamsize(row.size() * sizeof(float)));
    if (!in) throw std::runtime_error(path + ": PFM data truncated");
    if (swap)
      for (float& f : row) f = byte_swapped(f);
    for (long long x = 0; x < w; ++x)
      img.at(int(x), int(y)) = Pixel(row[3 * x], row[3 * x + 1], row[3 * x + 2]);
  }
  return img;
}

std::uint64_t Image::content_hash() const {
  std::uint64_t h = 0xcbf29ce484222325ull;
  auto mix = [&h](std::uint32_t word) {
    for (int i = 0; i < 4; ++i) {
      h ^= (word >> (8 * i)) & 0xffu;
      h *= 0x100000001b3ull;
    }
  };
  mix(std::uint32_t(width_));
  mix(std::uint32_t(height_));
  for (const Pixel& p : pixels_)
    for (int c = 0; c < 3; ++c) mix(std::bit_cast<std::uint32_t>(p[c]));
  return h;
}

std::string hash_hex(std::uint64_t hash) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hash));
  return buf;
}

}  // namespace tracer
