#include "spd_render.h"

#include "camera.h"
#include "intersector.h"
#include "nff_shading.h"
#include "offset_ray.h"
#include "optics.h"
#include "surface.h"

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace tracer {
namespace {

/// One ray tree of the SPD rules, per intersector type (so per structure and kind set).
template <class Isect>
class SpdTracer {
 public:
  SpdTracer(const Scene& scene, const Isect& isect, const std::vector<NffSurface>& surfaces)
      : scene_(&scene),
        isect_(isect),
        surfaces_(&surfaces),
        intensity_(spd_light_intensity(scene.lights.size())) {}

  /// Colour along `ray` at tree depth `depth`; sets *hit to whether it met a primitive.
  Color trace(const Ray& ray, int depth, RayCounts& counts, bool* hit_out = nullptr) const {
    const Hit hit = isect_.closest(ray);
    if (hit_out) *hit_out = hit.found();
    if (!hit.found()) return scene_->background;

    const Geometry& geo = isect_.geometry();
    SurfacePoint sp = surface_point(geo, ray, hit);
    // A sphere of negative radius shows its inside: its normal points inwards.
    if (!hit.is_plane() && geo.kind_of(hit.prim) == PrimitiveKind::Sphere &&
        geo.spheres[hit.prim].radius < 0.0f) {
      sp.n_geo = -sp.n_geo;
      sp.n_shade = -sp.n_shade;
    }
    // Vertex normals decide which side of a smooth triangle is its front.
    if (glm::dot(sp.n_geo, sp.n_shade) < 0.0f) sp.n_geo = -sp.n_geo;

    const NffSurface& s = (*surfaces_)[sp.material];
    const Vec3 d = glm::normalize(ray.dir);
    const bool transmits = s.transmittance > 0.0f;
    Vec3 ng = sp.n_geo, ns = sp.n_shade;
    bool entering = true;
    if (transmits && glm::dot(ng, d) > 0.0f) {  // two-sided: face the arriving ray
      ng = -ng;
      ns = -ns;
      entering = false;
    }

    Color color = nff_ambient(s, intensity_);
    for (const PointLight& light : scene_->lights) {
      const Vec3 to_light = light.position - sp.p;
      if (!(glm::dot(ns, to_light) > 0.0f)) continue;  // normal faces away: no shadow ray
      Ray shadow;
      shadow.org = offset_ray_origin(sp.p, glm::dot(ng, to_light) > 0.0f ? ng : -ng);
      shadow.dir = light.position - shadow.org;  // the light is at t = 1
      shadow.tmax = 1.0f;
      counts.shadow++;
      if (isect_.occluded(shadow)) continue;
      color += nff_direct(s, ns, -d, glm::normalize(to_light), intensity_ * light.color);
    }

    if (depth >= kSpdMaxDepth) return color;
    if (s.ks > 0.0f || transmits) {
      const Vec3 r = reflect(d, ns);
      Ray reflected;
      reflected.org = offset_ray_origin(sp.p, glm::dot(r, ng) >= 0.0f ? ng : -ng);
      reflected.dir = r;
      counts.reflection++;
      const Color rc = trace(reflected, depth + 1, counts);
      color += s.ks * rc;
    }
    if (transmits) {
      const float eta = entering ? 1.0f / s.ior : s.ior;
      // refract() needs a normal against the ray; an interpolated one may not be.
      const Vec3 n_against = glm::dot(ns, d) < 0.0f ? ns : ng;
      Vec3 t;
      if (refract(d, n_against, eta, t)) {
        Ray refracted;
        refracted.org = offset_ray_origin(sp.p, -ng);
        refracted.dir = glm::normalize(t);
        counts.refraction++;
        color += s.transmittance * trace(refracted, depth + 1, counts);
      }
    }
    return color;
  }

 private:
  const Scene* scene_;
  Isect isect_;
  const std::vector<NffSurface>* surfaces_;
  float intensity_;
};

PixelWindow resolve(const PixelWindow& w, int width, int height) {
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

RenderResult render_spd(const Scene& scene, const accel::AnyAccel& accel,
                        const SpdOptions& options) {
  const int width = options.width > 0 ? options.width : scene.camera.width;
  const int height = options.height > 0 ? options.height : scene.camera.height;
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
    throw std::invalid_argument("size: " + std::to_string(width) + "x" + std::to_string(height) +
                                " is not in [1, 16384]");
  const PixelWindow win = resolve(options.window, width, height);
  const int threads = resolve_threads(options.threads);

  std::vector<NffSurface> surfaces;
  surfaces.reserve(scene.materials.size());
  for (const Material& m : scene.materials) surfaces.push_back(nff_surface(m));

  // Colours at the (w+1) x (h+1) pixel corners of the window; each corner is one eye ray.
  const int cw = win.x1 - win.x0 + 1, ch = win.y1 - win.y0 + 1;
  std::vector<Color> corners(std::size_t(cw) * std::size_t(ch));
  std::vector<RayCounts> counts(static_cast<std::size_t>(threads));
  std::vector<accel::TraversalCounters> traversal(static_cast<std::size_t>(threads));
  const PinholeCamera camera(scene.camera, width, height);

  const auto start = std::chrono::steady_clock::now();
  with_intersector(scene.geometry, accel, options.count_traversal, [&](const auto& base) {
    std::atomic<int> next_row{0};
    auto worker = [&](int index) {
      const auto isect = base.with_counters(&traversal[std::size_t(index)]);
      const SpdTracer<std::decay_t<decltype(isect)>> tracer(scene, isect, surfaces);
      RayCounts& rc = counts[std::size_t(index)];
      // Rows are handed out dynamically; every corner's colour depends on nothing but its ray,
      // so the image and the summed counts are the same whichever thread traces which row.
      for (int row = next_row++; row < ch; row = next_row++) {
        for (int col = 0; col < cw; ++col) {
          Ray ray = camera.ray_through(float(win.x0 + col), float(win.y0 + row));
          ray.tmin = scene.camera.hither / glm::dot(ray.dir, camera.forward());
          rc.eye++;
          bool hit = false;
          corners[std::size_t(row) * std::size_t(cw) + std::size_t(col)] =
              tracer.trace(ray, 1, rc, &hit);
          if (hit) rc.eye_hits++;
        }
      }
    };
    if (threads == 1) {
      worker(0);
    } else {
      std::vector<std::thread> pool;
      for (int i = 0; i < threads; ++i) pool.emplace_back(worker, i);
      for (std::thread& t : pool) t.join();
    }
  });
  const auto stop = std::chrono::steady_clock::now();

  RenderResult result;
  result.render_ms = std::chrono::duration<double, std::milli>(stop - start).count();
  for (const RayCounts& c : counts) result.rays += c;
  for (const accel::TraversalCounters& t : traversal) result.traversal += t;
  result.image = Image(cw - 1, ch - 1);
  for (int y = 0; y + 1 < ch; ++y)
    for (int x = 0; x + 1 < cw; ++x) {
      const auto at = [&](int cx, int cy) {
        return corners[std::size_t(cy) * std::size_t(cw) + std::size_t(cx)];
      };
      result.image.at(x, y) = 0.25f * ((at(x, y) + at(x + 1, y)) + (at(x, y + 1) + at(x + 1, y + 1)));
    }
  return result;
}

}  // namespace tracer
