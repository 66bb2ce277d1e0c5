#include "ppm_integrator.h"

#include "map_needs.h"
#include "photon_map.h"
#include "photon_rng.h"
#include "photon_tracing.h"

#include "tracer/render_frame.h"
#include "tracer/whitted.h"


#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <mutex>
#include <numbers>
#include <string>
#include <type_traits>
#include <vector>

namespace photon {

namespace {

using Clock = std::chrono::steady_clock;
using DColor = glm::dvec3;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

constexpr int kMaxPhotons = std::numeric_limits<int>::max();
/// The k of a PPM gather: every photon within the radius (a gather that finds this many keeps
/// the nearest and shrinks the radius to the farthest of them).
constexpr int kGatherAll = 1 << 20;

/// A diffuse surface met by a camera path: where the photon flux density is estimated.
struct VisiblePoint {
  int x = 0, y = 0;         ///< Pixel, image coordinates.
  tracer::Vec3 p{0.0f};     ///< Position, world units.
  tracer::Vec3 n{0.0f};     ///< Unit shading normal, on the side the camera path arrived from.
  tracer::Color weight{0.0f};  ///< Path throughput x albedo / pi / samples per pixel.
};

/// What one worker's camera paths leave: the visible points, in the order they were met.
struct WorkerPoints {
  std::vector<VisiblePoint> points;
  int x = 0, y = 0;  ///< The pixel being traced.
  float inv_spp = 1.0f;
};

/// Whitted's shading with the photon estimate left for later: direct light now, and a visible
/// point wherever a diffuse surface reflects.
struct VisiblePointShading {
  WorkerPoints* out;

  template <class Tracer>
  tracer::Color diffuse(const Tracer& t, const tracer::DiffuseHit& h, const tracer::PathState& path,
                        tracer::RayCounts& counts) const {
    const tracer::Color radiance = t.direct(h.sp, h.n, h.n_geo, h.to_eye, h.response, counts);
    const tracer::Color brdf = h.response.albedo * (1.0f / std::numbers::pi_v<float>);
    if (std::max(brdf.x, std::max(brdf.y, brdf.z)) > 0.0f)
      out->points.push_back({out->x, out->y, h.sp.p, h.n, path.throughput * brdf * out->inv_spp});
    return radiance;
  }
  tracer::Color escaped(const tracer::Scene& scene, const tracer::PathState& path) const {
    return path.gathers == 0 ? scene.background : tracer::Color(0.0f);
  }
};

/// The tile loop's tracer: it is told each pixel before its camera rays (render_frame.h).
template <class Isect>
class VisiblePointTracer {
 public:
  VisiblePointTracer(const tracer::Scene& scene, const Isect& isect, WorkerPoints* out)
      : out_(out), whitted_(scene, isect, scene.render, VisiblePointShading{out}) {}
  void begin_pixel(int x, int y) const {
    out_->x = x;
    out_->y = y;
  }
  tracer::Color trace_eye(const tracer::Ray& ray, tracer::RayCounts& counts) const {
    return whitted_.trace_eye(ray, counts);
  }

 private:
  WorkerPoints* out_;
  tracer::Whitted<Isect, VisiblePointShading> whitted_;
};

/// The largest initial radius: 1/20 of the diagonal of the box around the scene's bounded
/// primitives (the photon integrator's automatic max_radius), 1 when there are none.
float auto_radius(const tracer::Scene& scene) {
  accel::Aabb box;
  for (const accel::Aabb& b : scene.geometry.primitive_bounds()) box.grow(b);
  const float diagonal = box.is_empty() ? 0.0f : glm::length(box.hi - box.lo);
  return diagonal > 0.0f && std::isfinite(diagonal) ? diagonal / 20.0f : 1.0f;
}

/// The progressive state of one visible point.
struct PointState {
  double r2 = 0.0;       ///< Radius squared, world units squared.
  double n = 0.0;        ///< Accumulated photon count (alpha-weighted).
  DColor tau{0.0};       ///< Accumulated flux, watts, scaled with the radius.
};

tracer::RenderResult render_ppm(const tracer::Scene& scene, const accel::AnyAccel& accel,
                                const tracer::RenderOptions& given, const nlohmann::json& knobs) {
  const auto start = Clock::now();
  const PpmParams params = knobs.get<PpmParams>();
  tracer::RenderOptions options = given;
  options.triangle_test = params.triangle;

  // 1. Camera paths: the direct image and the visible points.
  std::deque<WorkerPoints> workers;  // one per worker; deque: pointers stay valid
  std::mutex workers_mutex;
  const int spp = std::max(1, scene.camera.samples_per_pixel);
  tracer::RenderResult result = tracer::render_frame(
      scene, accel, options, tracer::FilmSampling::PixelSamples, [&](const auto& isect) {
        using Isect = std::decay_t<decltype(isect)>;
        WorkerPoints* w;
        {
          std::lock_guard<std::mutex> lock(workers_mutex);
          w = &workers.emplace_back();
        }
        w->inv_spp = 1.0f / float(spp);
        return VisiblePointTracer<Isect>(scene, isect, w);
      });
  // Each pixel is traced by one worker, its points in path order: a stable sort by pixel gives
  // the same list at any thread count.
  std::vector<VisiblePoint> points;
  for (WorkerPoints& w : workers) points.insert(points.end(), w.points.begin(), w.points.end());
  std::stable_sort(points.begin(), points.end(), [](const VisiblePoint& a, const VisiblePoint& b) {
    return a.y != b.y ? a.y < b.y : a.x < b.x;
  });
  const double camera_ms = ms_since(start);

  // 2. Photon passes, each gathered at every visible point with its own shrinking radius.
  // Photon powers are stored rounded to 8-bit shared-exponent mantissas (packed_power.h): photons
  // of equal power all carry the same relative error, up to 0.39 %, a bias that does not average
  // away. Each pass therefore traces a copy of the scene whose lights are scaled by
  // s = 2^frac(i phi) (a low-discrepancy sequence over one octave) and divides the flux it finds
  // by s: the rounding error's sign and size then vary from pass to pass and average out.
  const MapNeeds needs = map_needs(scene);
  const int threads = tracer::resolve_threads(options.threads);
  std::vector<std::array<Neighbors, 2>> found(std::size_t(std::max(1, threads)));  // per worker, per map
  std::uint64_t emitted = 0, stored = 0, photon_rays = 0;
  double trace_ms = 0.0, build_ms = 0.0, gather_ms = 0.0;
  constexpr int kChunk = 256;  // visible points per work item
  const int chunks = int((points.size() + kChunk - 1) / kChunk);
  tracer::Scene lit = scene;
  const auto trace_maps = [&](std::uint64_t pass_seed, float scale, PhotonMap (&maps)[2]) {
    for (std::size_t l = 0; l < lit.lights.size(); ++l) lit.lights[l].power_w = scene.lights[l].power_w * scale;
    int count = 0;
    for (const PhotonPass kind : {PhotonPass::Caustic, PhotonPass::Global}) {
      if (!(kind == PhotonPass::Caustic ? needs.caustic : needs.global)) continue;
      PassOptions po;
      po.pass = kind;
      po.target = std::uint64_t(params.photons_per_pass);
      po.max_depth = params.max_photon_depth;
      po.max_emitted = params.max_paths;
      po.seed = pass_seed;
      po.threads = options.threads;
      po.triangle_test = options.triangle_test;
      PassResult traced = trace_photon_pass(lit, accel, po);
      trace_ms += traced.trace_ms;
      emitted += traced.emitted;
      stored += traced.photons.size();
      photon_rays += traced.rays;
      const auto t0 = Clock::now();
      maps[count++] = PhotonMap(std::span<const Photon>(traced.photons), PhotonTreeParams{}, options.limits);
      build_ms += ms_since(t0);
    }
    return count;
  };
  const auto for_points = [&](auto&& body) {
    const auto t0 = Clock::now();
    tracer::parallel_items(threads, chunks, [&](int worker, int chunk) {
      const std::size_t end = std::min(points.size(), std::size_t(chunk + 1) * kChunk);
      for (std::size_t i = std::size_t(chunk) * kChunk; i < end; ++i) body(found[std::size_t(worker)].data(), i);
    });
    gather_ms += ms_since(t0);
  };

  // The initial radii: a given one everywhere, or ("auto") each visible point's distance to the
  // initial_photons-th nearest photon of a pilot pass (its own seed; its photons are not used in
  // the estimate, so the radius does not depend on the photons it counts), at most the cap.
  std::vector<PointState> state(points.size());
  const float cap = auto_radius(scene);
  if (params.initial_radius) {
    for (PointState& s : state) s.r2 = double(*params.initial_radius) * double(*params.initial_radius);
  } else {
    PhotonMap pilot[2];
    const int count = trace_maps(PhotonRng::mix(params.seed ^ 0x7f4a7c159e3779b9ull), 1.0f, pilot);
    for_points([&](Neighbors* nb, std::size_t i) {
      GatherParams g;
      g.k = params.initial_photons;
      g.max_radius = cap;
      std::vector<float> d2;
      for (int k = 0; k < count; ++k) {
        pilot[k].gather(points[i].p, points[i].n, g, nb[k]);
        for (const Neighbor& f : nb[k].items()) d2.push_back(f.d2);
      }
      float r2 = cap * cap;
      if (d2.size() >= std::size_t(g.k)) {
        std::nth_element(d2.begin(), d2.begin() + (g.k - 1), d2.end());
        r2 = std::min(r2, d2[std::size_t(g.k - 1)]);
      }
      state[i].r2 = std::max(double(r2), 1e-12 * double(cap) * double(cap));
    });
  }
  double initial_radius_mean = 0.0;
  for (const PointState& s : state) initial_radius_mean += std::sqrt(s.r2);
  if (!state.empty()) initial_radius_mean /= double(state.size());

  // The image after `passes` passes of the points' `states`: direct light plus, at every visible
  // point, weight x tau / (pi R^2 passes).
  tracer::Image direct = std::move(result.image);
  const auto compose = [&](tracer::Image image, const std::vector<PointState>& states, int passes) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      const VisiblePoint& v = points[i];
      const DColor e = states[i].tau / (std::numbers::pi * states[i].r2 * double(passes));
      image.at(v.x - options.window.x0, v.y - options.window.y0) += v.weight * tracer::Color(e);
    }
    return image;
  };
  std::vector<int> checkpoints;
  for (const int c : options.checkpoints)
    if (c >= 1 && c < params.passes) checkpoints.push_back(c);
  std::sort(checkpoints.begin(), checkpoints.end());
  checkpoints.erase(std::unique(checkpoints.begin(), checkpoints.end()), checkpoints.end());
  std::size_t next_checkpoint = 0;

  for (int pass = 0; pass < params.passes; ++pass) {
    if (next_checkpoint < checkpoints.size() && checkpoints[next_checkpoint] == pass) {
      // A render stopped here would compose the same state with the same pass count.
      result.checkpoints.emplace_back(pass, compose(direct, state, pass));
      ++next_checkpoint;
    }
    PhotonMap maps[2];
    const double frac = std::fmod(double(pass + 1) * 0.6180339887498949, 1.0);
    const float scale = float(std::exp2(frac));
    const int count = trace_maps(PhotonRng::mix(params.seed ^ PhotonRng::mix(std::uint64_t(pass) + 1)), scale, maps);
    const double unscale = 1.0 / double(scale);
    for_points([&](Neighbors* nb, std::size_t i) {
      PointState& s = state[i];
      GatherParams g;
      g.k = kGatherAll;
      g.max_radius = float(std::sqrt(s.r2));
      double r2 = s.r2;
      for (int k = 0; k < count; ++k) {
        maps[k].gather(points[i].p, points[i].n, g, nb[k]);
        if (nb[k].full()) r2 = std::min(r2, double(nb[k].max_d2()));  // the nearest 2^20 only
      }
      if (r2 < s.r2) {  // a smaller disc: the flux so far scaled to it, as the update does
        s.tau *= r2 / s.r2;
        s.r2 = r2;
      }
      double m = 0.0;
      DColor flux(0.0);
      for (int k = 0; k < count; ++k)
        for (const Neighbor& f : nb[k].items()) {
          if (double(f.d2) > r2) continue;
          flux += DColor(maps[k].photon(f.slot).power());
          m += 1.0;
        }
      if (m == 0.0) return;
      const double n_new = s.n + double(params.alpha) * m;
      const double r2_new = r2 * n_new / (s.n + m);
      s.tau = (s.tau + flux * unscale) * (r2_new / r2);
      s.n = n_new;
      s.r2 = r2_new;
    });
  }

  // 3. The image.
  result.image = compose(std::move(direct), state, params.passes);  // the direct image is not needed after
  double mean_radius = 0.0;
  for (const PointState& s : state) mean_radius += std::sqrt(s.r2);
  result.rays.photon = photon_rays;
  result.render_ms = ms_since(start);
  result.stats = {{"params", params},
                  {"visible_points", points.size()},
                  {"photons_stored", stored},
                  {"photon_paths", emitted},
                  {"mean_initial_radius", initial_radius_mean},
                  {"mean_final_radius", points.empty() ? 0.0 : mean_radius / double(points.size())},
                  {"timings",
                   {{"camera_ms", camera_ms},
                    {"photon_trace_ms", trace_ms},
                    {"map_build_ms", build_ms},
                    {"gather_ms", gather_ms}}}};
  return result;
}

const knobs::AnyKnobTable& ppm_knobs() { return PpmParams::knobs(); }

// Progressive photon mapping's error is not all noise: the blur its radius has not yet shrunk
// away is a bias that independent halves share. R^2 shrinks as passes^-(1 - alpha), and the bias
// with it (Knaus and Zwicker 2011): order 1/3 at alpha 2/3.
double ppm_bias_order(const nlohmann::json& params) {
  return 1.0 - double(PpmParams::knobs().complete(params).get<PpmParams>().alpha);
}

std::string ppm_summary(const nlohmann::json& stats) {
  char line[320];
  std::snprintf(line, sizeof line,
                "ppm      %d passes: %llu photons stored from %llu paths, %llu visible points, "
                "mean radius %.4g -> %.4g\n",
                stats.at("params").get<PpmParams>().passes, stats.at("photons_stored").get<unsigned long long>(),
                stats.at("photon_paths").get<unsigned long long>(),
                stats.at("visible_points").get<unsigned long long>(), stats.at("mean_initial_radius").get<double>(),
                stats.at("mean_final_radius").get<double>());
  return line;
}

}  // namespace

const knobs::KnobTable<PpmParams>& PpmParams::knobs() {
  using K = knobs::Knob<PpmParams>;
  static const knobs::KnobTable<PpmParams> table(
      "ppm",
      {K::integer("passes", &PpmParams::passes, 1, 1000000, "passes",
                  "Photon passes (each photons_per_pass per map): error falls as N^-1/3 in RMSE.")
           // Its convergence front: the same recipe with 4x the passes of the longest value as
           // the reference.
           .front({"[1, 2, 4, 8, 16, 32, 64]", "", R"({"passes": 256})", "", true}),
       K::integer("photons_per_pass", &PpmParams::photons_per_pass, 1, kMaxPhotons, "photons",
                  "Photons stored per map (caustic and global) per pass."),
       K::integer("max_paths", &PpmParams::max_paths, 0, 1ull << 40, "paths",
                  "Photon paths one map may emit in a pass (0 = the tracer's own cap); a map cut "
                  "short stays unbiased."),
       K::number_or_auto("initial_radius", &PpmParams::initial_radius, 0.0, 3.0e38, "world units",
                         "Radius every visible point starts with; auto = the distance to the "
                         "initial_photons-th photon of a pilot pass.")
           .open_below(),
       K::integer("initial_photons", &PpmParams::initial_photons, 1, 1 << 20, "photons",
                  "Photons of the pilot pass within an automatic initial radius."),
       K::number("alpha", &PpmParams::alpha, 0.0, 1.0, "",
                 "Share of new photons kept at each pass: 2/3 balances bias and variance.")
           .open_below(),
       K::integer("max_photon_depth", &PpmParams::max_photon_depth, 1, 1000, "bounces",
                  "Surface interactions per photon path before it is dropped."),
       K::integer(knobs::kSeedKnob, &PpmParams::seed, 0, ~0ull, "",
                  "Seed of the photon paths; pass i draws from a seed of its own derived from it."),
       tracer::triangle_knob(&PpmParams::triangle)});
  return table;
}

const tracer::Integrator& ppm_integrator() {
  static constexpr tracer::Integrator kPpm{
      "ppm",
      "progressive photon mapping (Hachisuka et al. 2008, alpha 2/3): the consistent reference for "
      "the photon integrator's knobs",
      ppm_knobs, render_ppm, ppm_summary, nullptr,
      // The reference of the photon integrator's fronts: 256 passes of 50,000 photons per map
      // (12.8 million per map and half).
      R"({"passes": 256, "photons_per_pass": 50000})", "passes", ppm_bias_order};
  return kPpm;
}

}  // namespace photon
