#pragma once
// The one tile-parallel render loop behind every integrator. Include it only in the one .cpp
// file of an integrator: render_frame() instantiates that integrator once per structure, kind
// set and counting flag (with_intersector), and that is where the compile time goes.

#include "camera.h"
#include "intersector.h"
#include "naive_reference.h"
#include "parallel.h"
#include "render.h"

#include <chrono>
#include <concepts>
#include <cstdint>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

namespace tracer {

/// Which points of the film an integrator traces camera rays through.
enum class FilmSampling : std::uint8_t {
  PixelSamples,  ///< samples_per_pixel jittered rays per pixel (sample_offset), averaged.
  PixelCorners,  ///< One ray per pixel corner; each pixel is the mean of its four (SPD rules).
};

/// How a frame samples its film: the sampling rule and, for PixelSamples, how many jittered rays
/// per pixel with which jitter seed. Made implicitly from a FilmSampling (the scene's spp, seed 0).
struct FilmSpec {
  FilmSampling sampling = FilmSampling::PixelSamples;  ///< Which points of the film are traced.
  int samples_per_pixel = 0;  ///< PixelSamples: rays per pixel, >= 1; 0 = the scene camera's.
  std::uint64_t seed = 0;     ///< PixelSamples: seed of the sub-pixel jitter (sample_offset).

  FilmSpec(FilmSampling s, int spp = 0, std::uint64_t jitter_seed = 0)  // NOLINT: implicit
      : sampling(s), samples_per_pixel(spp), seed(jitter_seed) {}
};

namespace render_frame_detail {

/// Tile edge, in film samples: small enough to balance the threads, large enough to share caches.
inline constexpr int kTileSize = 16;

/// Everything about a frame that does not depend on the integrator.
struct Frame {
  PinholeCamera camera;     ///< The scene's camera at the render's image size.
  PixelWindow window;       ///< The window, resolved against the image size.
  FilmSampling film;        ///< What a film sample is.
  int grid_w = 0;           ///< Film samples per row: window pixels, or their corners.
  int grid_h = 0;           ///< Rows of film samples.
  int tiles_x = 0;          ///< Tiles per row of the sample grid.
  int tiles = 0;            ///< Tiles in all.
  int threads = 1;          ///< Worker threads.
  int spp = 1;              ///< Samples per pixel (PixelSamples).
  std::uint64_t seed = 0;   ///< Seed of the sub-pixel jitter (PixelSamples).
};

/// Per-worker tallies, summed after the join (integer sums: order does not matter). Each on its
/// own cache lines: the workers bump their counts on every ray, and two tallies sharing a line
/// would bounce it between the cores (false sharing).
struct alignas(64) ThreadTally {
  RayCounts rays;
  accel::TraversalCounters traversal;
};

/// The frame of `options` on `scene`; throws std::invalid_argument naming a bad option.
Frame make_frame(const Scene& scene, const RenderOptions& options, FilmSpec film);

/// The image from the grid of film samples: the grid itself, or every pixel the mean of its four
/// corners.
Image resolve_image(const Frame& frame, const std::vector<Color>& grid);

/// The scalar type a tracer computes in: its `Scalar` member type, or float.
template <class Tracer, class = void>
struct TracerScalar {
  using type = float;
};
template <class Tracer>
struct TracerScalar<Tracer, std::void_t<typename Tracer::Scalar>> {
  using type = typename Tracer::Scalar;
};

/// A tracer whose camera rays can be found as packets: it shades a camera ray from a hit found
/// elsewhere (trace_eye_hit), its intersector answers packets (closest_packet) and counts no
/// traversal (counting renders keep the single-ray statistics), and it keeps no per-pixel state.
template <class Tracer>
concept PacketCameraTracer =
    requires(const Tracer& t, const Ray& ray, const Hit& hit, RayCounts& counts, std::span<const Ray> rays,
             std::span<Hit> hits) {
      { t.trace_eye_hit(ray, hit, counts) } -> std::same_as<Color>;
      t.intersector().closest_packet(rays, hits);
      requires !std::decay_t<decltype(t.intersector())>::kCounting;
    } && !requires(const Tracer& t) { t.begin_pixel(0, 0); };

/// Side of the square block of film samples whose camera rays go as one packet.
inline constexpr int kPacketSide = 4;

/// trace_tile for a PacketCameraTracer: the camera rays of each 4x4 block of film samples (one
/// sample index at a time) are intersected as one packet, then shaded one by one, or together
/// by a tracer with trace_eye_packet. Each ray gets the hit it would get alone, and each sample
/// sums in the same order, so the image is the single-ray loop's to the bit.
template <class Camera, class Tracer>
void trace_tile_packets(const Frame& f, const Camera& camera, int gx0, int gy0, int gx1, int gy1,
                        const Tracer& tracer, RayCounts& rays, std::vector<Color>& grid) {
  constexpr int kLanes = kPacketSide * kPacketSide;
  const float inv_spp = 1.0f / float(f.spp);
  const bool corners = f.film == FilmSampling::PixelCorners;
  for (int by = gy0; by < gy1; by += kPacketSide)
    for (int bx = gx0; bx < gx1; bx += kPacketSide) {
      int gxs[kLanes], gys[kLanes], n = 0;
      for (int gy = by; gy < std::min(by + kPacketSide, gy1); ++gy)
        for (int gx = bx; gx < std::min(bx + kPacketSide, gx1); ++gx) {
          gxs[n] = gx;
          gys[n++] = gy;
        }
      Color sum[kLanes];
      for (int i = 0; i < n; ++i) sum[i] = Color(0.0f);
      for (int s = 0; s < (corners ? 1 : f.spp); ++s) {
        Ray packet[kLanes];
        Hit hits[kLanes];
        for (int i = 0; i < n; ++i) {
          const int x = f.window.x0 + gxs[i], y = f.window.y0 + gys[i];
          float jx = 0.5f, jy = 0.5f;
          if (!corners) sample_offset(x, y, s, f.spp, jx, jy, f.seed);
          packet[i] = corners ? camera.ray_through(float(x), float(y)) : camera.primary_ray(x, y, jx, jy);
        }
        tracer.intersector().closest_packet(std::span<const Ray>(packet, std::size_t(n)),
                                            std::span<Hit>(hits, std::size_t(n)));
        Color c[kLanes];
        // A tracer that can also send its first shadow rays as packets shades the hits together.
        if constexpr (requires { tracer.trace_eye_packet(std::span<const Ray>(), std::span<const Hit>(), rays, std::span<Color>()); })
          tracer.trace_eye_packet(std::span<const Ray>(packet, std::size_t(n)), std::span<const Hit>(hits, std::size_t(n)),
                                  rays, std::span<Color>(c, std::size_t(n)));
        else
          for (int i = 0; i < n; ++i) c[i] = tracer.trace_eye_hit(packet[i], hits[i], rays);
        for (int i = 0; i < n; ++i) {
          if (corners)
            sum[i] = c[i];
          else
            sum[i] += c[i];
        }
      }
      for (int i = 0; i < n; ++i)
        grid[std::size_t(gys[i]) * std::size_t(f.grid_w) + std::size_t(gxs[i])] =
            corners || f.spp == 1 ? sum[i] : sum[i] * inv_spp;
    }
}

/// Traces the film samples of one tile into `grid`, with camera rays from `camera` (a
/// PinholeCameraT of the tracer's scalar type).
template <class Camera, class Tracer>
void trace_tile(const Frame& f, const Camera& camera, int tile, const Tracer& tracer,
                RayCounts& rays, std::vector<Color>& grid) {
  const int gx0 = (tile % f.tiles_x) * kTileSize, gy0 = (tile / f.tiles_x) * kTileSize;
  const int gx1 = std::min(gx0 + kTileSize, f.grid_w), gy1 = std::min(gy0 + kTileSize, f.grid_h);
  if constexpr (PacketCameraTracer<Tracer>) {
    trace_tile_packets(f, camera, gx0, gy0, gx1, gy1, tracer, rays, grid);
    return;
  }
  const float inv_spp = 1.0f / float(f.spp);
  for (int gy = gy0; gy < gy1; ++gy)
    for (int gx = gx0; gx < gx1; ++gx) {
      const int x = f.window.x0 + gx, y = f.window.y0 + gy;
      // A tracer that keeps per-pixel state (a progressive reference's visible points) is told
      // which pixel (PixelCorners: which corner) the camera rays that follow belong to.
      if constexpr (requires { tracer.begin_pixel(x, y); }) tracer.begin_pixel(x, y);
      Color c;
      if (f.film == FilmSampling::PixelCorners) {
        c = tracer.trace_eye(camera.ray_through(float(x), float(y)), rays);
      } else {
        Color sum(0.0f);
        for (int s = 0; s < f.spp; ++s) {
          float jx = 0.5f, jy = 0.5f;
          sample_offset(x, y, s, f.spp, jx, jy, f.seed);
          sum += tracer.trace_eye(camera.primary_ray(x, y, jx, jy), rays);
        }
        c = f.spp == 1 ? sum : sum * inv_spp;
      }
      grid[std::size_t(gy) * std::size_t(f.grid_w) + std::size_t(gx)] = c;
    }
}

/// The tile loop of every render: `dispatch(body)` calls body(intersector) once, with the
/// intersector the frame is traced through (with_intersector's choice, or a given one).
template <class Dispatch, class MakeTracer>
RenderResult render_frame_with(const Scene& scene, const RenderOptions& options, FilmSpec film,
                               Dispatch&& dispatch, MakeTracer&& make_tracer) {
  const Frame frame = make_frame(scene, options, film);
  std::vector<Color> grid(std::size_t(frame.grid_w) * std::size_t(frame.grid_h));
  std::vector<ThreadTally> tallies(static_cast<std::size_t>(frame.threads));
  prepare_threads(frame.threads);  // started before the clock, as the structure is built before it

  const auto start = std::chrono::steady_clock::now();
  dispatch([&](const auto& base) {
    using Isect = std::decay_t<decltype(base)>;
    using Tracer = std::decay_t<decltype(make_tracer(base))>;
    using Scalar = typename TracerScalar<Tracer>::type;
    // The float camera of the frame, or the same camera computed in the tracer's scalar type.
    const PinholeCameraT<Scalar> camera = [&] {
      if constexpr (std::is_same_v<Scalar, float>)
        return frame.camera;
      else
        return PinholeCameraT<Scalar>(scene.camera, frame.camera.width(), frame.camera.height());
    }();
    std::vector<std::optional<Tracer>> tracers(static_cast<std::size_t>(frame.threads));
    parallel_items(frame.threads, frame.tiles, [&](int worker, int tile) {
      ThreadTally& tally = tallies[std::size_t(worker)];
      std::optional<Tracer>& tracer = tracers[std::size_t(worker)];
      if (!tracer)
        tracer.emplace(make_tracer(Isect::kCounting ? base.with_counters(&tally.traversal) : base));
      trace_tile(frame, camera, tile, *tracer, tally.rays, grid);
    });
  });
  const auto stop = std::chrono::steady_clock::now();

  RenderResult result;
  result.image = resolve_image(frame, grid);
  result.render_ms = std::chrono::duration<double, std::milli>(stop - start).count();
  for (const ThreadTally& t : tallies) {
    result.rays += t.rays;
    result.traversal += t.traversal;
  }
  return result;
}

}  // namespace render_frame_detail

/// Renders `scene` through `accel` in tiles on every worker thread. `make_tracer(isect)` is called
/// once per worker with that worker's intersector (its own traversal counters) and returns the
/// worker's tracer: an object with `Color trace_eye(const Ray&, RayCounts&) const` that traces one
/// camera ray and counts it (a tracer with `using Scalar = double` gets RayD camera rays), and
/// optionally `void begin_pixel(int x, int y) const`, called before the camera rays of each pixel.
/// Every film sample depends on its ray alone, so the image and the summed counts are the same at
/// any thread count. A worker's exception is rethrown here.
template <class MakeTracer>
RenderResult render_frame(const Scene& scene, const accel::AnyAccel& accel,
                          const RenderOptions& options, FilmSpec film,
                          MakeTracer&& make_tracer) {
  return render_frame_detail::render_frame_with(
      scene, options, film,
      [&](auto&& body) { with_intersector(scene.geometry, accel, options.count_traversal, options.triangle_test, body); },
      make_tracer);
}

/// The same tile loop through one given intersector instead of a built structure: the naive
/// reference in double (tracer/naive_reference.h). Traversal counters stay zero.
template <class Isect, class MakeTracer>
RenderResult render_frame_on(const Scene& scene, const Isect& isect, const RenderOptions& options,
                             FilmSpec film, MakeTracer&& make_tracer) {
  return render_frame_detail::render_frame_with(
      scene, options, film, [&](auto&& body) { body(isect); }, make_tracer);
}

/// render_frame in float through `accel`, or with Precision::Double render_frame_on the naive
/// reference in double (the structure is not used).
template <class MakeTracer>
RenderResult render_frame_at(Precision precision, const Scene& scene, const accel::AnyAccel& accel,
                             const RenderOptions& options, FilmSpec film,
                             MakeTracer&& make_tracer) {
  if (precision == Precision::Double)
    return render_frame_on(scene, NaiveReference<double>(scene.geometry, options.triangle_test), options, film,
                           make_tracer);
  return render_frame(scene, accel, options, film, make_tracer);
}

}  // namespace tracer
