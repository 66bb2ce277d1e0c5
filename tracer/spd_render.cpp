#include "spd_render.h"

#include "intersector.h"
#include "nff_shading.h"
#include "offset_ray.h"
#include "optics.h"
#include "render_frame.h"
#include "surface.h"

#include <type_traits>
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

  /// Colour along an eye ray (tree depth 1); counts it, and whether it hit.
  Color trace_eye(const Ray& ray, RayCounts& counts) const {
    counts.eye++;
    bool hit = false;
    const Color color = trace(ray, 1, counts, &hit);
    if (hit) counts.eye_hits++;
    return color;
  }

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
      // Leaves on the light's side; t = 1 just short of the light.
      const Ray shadow =
          segment_to(offset_ray_origin(sp, glm::dot(ng, to_light) > 0.0f ? ng : -ng), light.position);
      counts.shadow++;
      if (isect_.occluded(shadow)) continue;
      color += nff_direct(s, ns, -d, glm::normalize(to_light), intensity_ * light.color);
    }

    if (depth >= kSpdMaxDepth) return color;
    if (s.ks > 0.0f || transmits) {
      const Vec3 r = reflect(d, ns);
      Ray reflected;
      reflected.org = offset_ray_origin(sp, glm::dot(r, ng) >= 0.0f ? ng : -ng);
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
        refracted.org = offset_ray_origin(sp, -ng);
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

RenderResult render_spd(const Scene& scene, const accel::AnyAccel& accel,
                        const RenderOptions& options, const nlohmann::json&) {
  std::vector<NffSurface> surfaces;
  surfaces.reserve(scene.materials.size());
  for (const Material& m : scene.materials) surfaces.push_back(nff_surface(m));
  return render_frame(scene, accel, options, FilmSampling::PixelCorners,
                      [&scene, &surfaces](const auto& isect) {
                        return SpdTracer<std::decay_t<decltype(isect)>>(scene, isect, surfaces);
                      });
}

nlohmann::json spd_params(const nlohmann::json& given) { return no_params("spd", given); }

}  // namespace

const Integrator& spd_integrator() {
  static constexpr Integrator kSpd{
      "spd",
      "Eric Haines' SPD test rules: eye rays at pixel corners, tree depth 5, NFF shading",
      spd_params, render_spd};
  return kSpd;
}

}  // namespace tracer
