#include "render.h"

#include "camera.h"
#include "intersector.h"
#include "whitted.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace tracer {

namespace {

/// Tile edge, pixels: small enough to balance the threads, large enough to share caches.
constexpr int kTileSize = 16;

std::uint64_t mix64(std::uint64_t z) {  // splitmix64 finaliser
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

float unit_float(std::uint64_t bits) {
  return float(bits >> 40) * 0x1.0p-24f;
}  // [0, 1)

/// Per-thread tallies, summed after the join (integer sums: order does not matter).
struct ThreadTally {
  RayCounts rays;
  accel::TraversalCounters traversal;
};

template <class Isect>
void render_tiles(const Scene& scene, const PinholeCamera& camera, const Isect& base_isect,
                  int threads, Image& image, ThreadTally& total) {
  const int w = camera.width(), h = camera.height();
  const int tiles_x = (w + kTileSize - 1) / kTileSize;
  const int tiles_y = (h + kTileSize - 1) / kTileSize;
  const int tile_count = tiles_x * tiles_y;
  const int spp = std::max(1, scene.camera.samples_per_pixel);
  const float inv_spp = 1.0f / float(spp);

  std::atomic<int> next_tile{0};
  std::vector<ThreadTally> tallies(static_cast<std::size_t>(threads));
  std::exception_ptr failure;
  std::mutex failure_mutex;

  auto worker = [&](int index) {
    try {
      ThreadTally& tally = tallies[std::size_t(index)];
      const Isect isect =
          Isect::kCounting ? base_isect.with_counters(&tally.traversal) : base_isect;
      const Whitted<Isect> integrator(scene, isect);
      for (int tile = next_tile++; tile < tile_count; tile = next_tile++) {
        const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
        const int x1 = std::min(x0 + kTileSize, w), y1 = std::min(y0 + kTileSize, h);
        for (int y = y0; y < y1; ++y)
          for (int x = x0; x < x1; ++x) {
            Color sum(0.0f);
            for (int s = 0; s < spp; ++s) {
              float jx = 0.5f, jy = 0.5f;
              sample_offset(x, y, s, spp, jx, jy);
              sum += integrator.trace_eye(camera.primary_ray(x, y, jx, jy), tally.rays);
            }
            image.at(x, y) = spp == 1 ? sum : sum * inv_spp;
          }
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
      next_tile = tile_count;  // stop the others early
    }
  };

  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(worker, i);
  worker(0);
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  for (const ThreadTally& t : tallies) {
    total.rays += t.rays;
    total.traversal += t.traversal;
  }
}

}  // namespace

int resolve_threads(int threads) {
  if (threads > 0) return threads;
  return std::max(1, int(std::thread::hardware_concurrency()));
}

void sample_offset(int x, int y, int s, int spp, float& jx, float& jy) {
  if (spp <= 1) {
    jx = jy = 0.5f;
    return;
  }
  const int m = int(std::ceil(std::sqrt(double(spp))));  // strata per row
  const int rows = (spp + m - 1) / m;
  const std::uint64_t key =
      (std::uint64_t(std::uint32_t(y)) << 32 | std::uint32_t(x)) * 0x9e3779b97f4a7c15ull;
  const std::uint64_t r = mix64(key ^ mix64(std::uint64_t(s) + 1));
  jx = (float(s % m) + unit_float(r)) / float(m);
  jy = (float(s / m) + unit_float(mix64(r))) / float(rows);
  jx = std::min(jx, 0x1.fffffep-1f);
  jy = std::min(jy, 0x1.fffffep-1f);
}

RenderResult render(const Scene& scene, const accel::AnyAccel& accel,
                    const RenderOptions& options) {
  if (options.threads < 0)
    throw std::invalid_argument("threads must be >= 0, got " + std::to_string(options.threads));
  if (options.width < 0 || options.height < 0)
    throw std::invalid_argument("image size must be >= 0, got " + std::to_string(options.width) +
                                "x" + std::to_string(options.height));
  const int width = options.width ? options.width : scene.camera.width;
  const int height = options.height ? options.height : scene.camera.height;
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("image size must be > 0, got " + std::to_string(width) + "x" +
                                std::to_string(height));

  const PinholeCamera camera(scene.camera, width, height);
  const int tiles = ((width + kTileSize - 1) / kTileSize) * ((height + kTileSize - 1) / kTileSize);
  const int threads = std::min(resolve_threads(options.threads), tiles);

  RenderResult result;
  result.image = Image(width, height);
  ThreadTally total;
  const auto start = std::chrono::steady_clock::now();
  with_intersector(scene.geometry, accel, options.count_traversal, [&](const auto& isect) {
    render_tiles(scene, camera, isect, threads, result.image, total);
  });
  const auto stop = std::chrono::steady_clock::now();
  result.render_ms = std::chrono::duration<double, std::milli>(stop - start).count();
  result.rays = total.rays;
  result.traversal = total.traversal;
  return result;
}

}  // namespace tracer
