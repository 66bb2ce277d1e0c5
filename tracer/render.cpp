#include "render.h"

#include "render_frame.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tracer {

namespace {

/// Largest image side, pixels (the scene format's limit).
constexpr int kMaxImageSide = 65536;
/// Most samples per pixel (the scene format's limit).
constexpr int kMaxSamplesPerPixel = 65536;

std::uint64_t mix64(std::uint64_t z) {  // splitmix64 finaliser
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

float unit_float(std::uint64_t bits) {
  return float(bits >> 40) * 0x1.0p-24f;
}  // [0, 1)

PixelWindow resolve_window(const PixelWindow& w, int width, int height) {
  PixelWindow r = w;
  if (r.x1 < 0) r.x1 = width;
  if (r.y1 < 0) r.y1 = height;
  if (r.x0 < 0 || r.y0 < 0 || r.x0 >= r.x1 || r.y0 >= r.y1 || r.x1 > width || r.y1 > height)
    throw std::invalid_argument("window: [" + std::to_string(r.x0) + ", " + std::to_string(r.x1) +
                                ") x [" + std::to_string(r.y0) + ", " + std::to_string(r.y1) +
                                ") is not inside the " + std::to_string(width) + "x" +
                                std::to_string(height) + " image");
  return r;
}

}  // namespace

namespace render_frame_detail {

Frame make_frame(const Scene& scene, const RenderOptions& options, FilmSpec film) {
  if (options.threads < 0)
    throw std::invalid_argument("threads must be >= 0, got " + std::to_string(options.threads));
  if (options.width < 0 || options.height < 0)
    throw std::invalid_argument("image size must be >= 0, got " + std::to_string(options.width) +
                                "x" + std::to_string(options.height));
  const int width = options.width ? options.width : scene.camera.width;
  const int height = options.height ? options.height : scene.camera.height;
  if (width <= 0 || height <= 0 || width > kMaxImageSide || height > kMaxImageSide)
    throw std::invalid_argument("image size must be in [1, " + std::to_string(kMaxImageSide) +
                                "] per side, got " + std::to_string(width) + "x" +
                                std::to_string(height));
  if (film.samples_per_pixel < 0 || film.samples_per_pixel > kMaxSamplesPerPixel)
    throw std::invalid_argument("samples per pixel must be in [1, " +
                                std::to_string(kMaxSamplesPerPixel) + "], got " +
                                std::to_string(film.samples_per_pixel));
  Frame f{PinholeCamera(scene.camera, width, height), resolve_window(options.window, width, height),
          film.sampling};
  const int extra = film.sampling == FilmSampling::PixelCorners ? 1 : 0;
  f.grid_w = f.window.x1 - f.window.x0 + extra;
  f.grid_h = f.window.y1 - f.window.y0 + extra;
  f.tiles_x = (f.grid_w + kTileSize - 1) / kTileSize;
  f.tiles = f.tiles_x * ((f.grid_h + kTileSize - 1) / kTileSize);
  f.threads = std::min(resolve_threads(options.threads), f.tiles);
  f.spp = film.samples_per_pixel > 0 ? film.samples_per_pixel
                                     : std::max(1, scene.camera.samples_per_pixel);
  f.seed = film.seed;
  return f;
}

Image resolve_image(const Frame& f, const std::vector<Color>& grid) {
  const int w = f.window.x1 - f.window.x0, h = f.window.y1 - f.window.y0;
  Image image(w, h);
  const auto at = [&](int gx, int gy) {
    return grid[std::size_t(gy) * std::size_t(f.grid_w) + std::size_t(gx)];
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      image.at(x, y) = f.film == FilmSampling::PixelCorners
                           ? 0.25f * ((at(x, y) + at(x + 1, y)) + (at(x, y + 1) + at(x + 1, y + 1)))
                           : at(x, y);
  return image;
}

}  // namespace render_frame_detail

RenderResult render(const Scene& scene, const accel::AnyAccel& accel, const RenderOptions& options,
                    const Integrator& integrator, const nlohmann::json& params) {
  const nlohmann::json full = integrator.params(params);
  render_frame_detail::make_frame(scene, options, FilmSampling::PixelSamples);  // checks options
  if (integrator.check) integrator.check(scene, options, full);
  return integrator.render(scene, accel, options, full);
}

void sample_offset(int x, int y, int s, int spp, float& jx, float& jy, std::uint64_t seed) {
  if (spp <= 1) {
    jx = jy = 0.5f;
    return;
  }
  // A rows x m grid of equal strata with exactly one sample each (rows the largest divisor of
  // spp not above its square root), so the samples are uniform over the pixel and their mean is
  // an unbiased estimate of its integral. (A ceil(sqrt(spp))-wide grid left the last row short
  // when spp is not a square: 8 samples on 3 x 3 strata under-sample the bottom third.)
  int rows = int(std::sqrt(double(spp)));
  while (rows > 1 && spp % rows != 0) --rows;
  const int m = spp / rows;  // strata per row
  std::uint64_t key =
      (std::uint64_t(std::uint32_t(y)) << 32 | std::uint32_t(x)) * 0x9e3779b97f4a7c15ull;
  if (seed != 0) key ^= mix64(seed ^ 0xd1b54a32d192ed03ull);  // seed 0: the historical pattern
  const std::uint64_t r = mix64(key ^ mix64(std::uint64_t(s) + 1));
  jx = (float(s % m) + unit_float(r)) / float(m);
  jy = (float(s / m) + unit_float(mix64(r))) / float(rows);
  jx = std::min(jx, 0x1.fffffep-1f);
  jy = std::min(jy, 0x1.fffffep-1f);
}

}  // namespace tracer
