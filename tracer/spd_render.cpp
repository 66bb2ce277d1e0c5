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
  using Scalar = typename Isect::Scalar;  ///< float, or double for the naive reference.
  using V = Vec3T<Scalar>;
  using R = RayT<Scalar>;

  SpdTracer(const Scene& scene, const Isect& isect, const std::vector<NffSurface>& surfaces)
      : scene_(&scene),
        isect_(isect),
        surfaces_(&surfaces),
        intensity_(spd_light_intensity(scene.lights.size())) {}

  /// Colour along an eye ray (tree depth 1); counts it, and whether it hit.
  Color trace_eye(const R& ray, RayCounts& counts) const { return trace_eye_hit(ray, isect_.closest(ray), counts); }

  /// trace_eye for a camera ray whose closest hit the caller has already found (a packet of
  /// camera rays, render_frame.h).
  Color trace_eye_hit(const R& ray, const HitT<Scalar>& hit, RayCounts& counts) const {
    counts.eye++;
    if (hit.found()) counts.eye_hits++;
    return shade(ray, hit, 1, counts);
  }

  /// The intersector every ray of this tracer goes through.
  const Isect& intersector() const { return isect_; }

  /// Colour along `ray` at tree depth `depth`.
  Color trace(const R& ray, int depth, RayCounts& counts) const { return shade(ray, isect_.closest(ray), depth, counts); }

  /// trace() from the ray's closest hit on.
  Color shade(const R& ray, const HitT<Scalar>& hit, int depth, RayCounts& counts) const {
    if (!hit.found()) return scene_->background;

    const Geometry& geo = isect_.geometry();
    SurfacePointT<Scalar> sp = surface_point(geo, ray, hit);
    // A sphere of negative radius shows its inside: its normal points inwards.
    if (!hit.is_plane() && geo.kind_of(hit.prim) == PrimitiveKind::Sphere &&
        geo.spheres[hit.prim].radius < 0.0f) {
      sp.n_geo = -sp.n_geo;
      sp.n_shade = -sp.n_shade;
    }
    // Vertex normals decide which side of a smooth triangle is its front.
    if (glm::dot(sp.n_geo, sp.n_shade) < Scalar(0)) sp.n_geo = -sp.n_geo;

    const NffSurface& s = (*surfaces_)[sp.material];
    const V d = glm::normalize(ray.dir);
    const bool transmits = s.transmittance > 0.0f;
    V ng = sp.n_geo, ns = sp.n_shade;
    bool entering = true;
    if (transmits && glm::dot(ng, d) > Scalar(0)) {  // two-sided: face the arriving ray
      ng = -ng;
      ns = -ns;
      entering = false;
    }

    Color color = nff_ambient(s, intensity_);
    for (const PointLight& light : scene_->lights) {
      const V light_position(light.position);
      const V to_light = light_position - sp.p;
      if (!(glm::dot(ns, to_light) > Scalar(0))) continue;  // normal faces away: no shadow ray
      // Leaves on the light's side; t = 1 just short of the light.
      const R shadow = segment_to(
          offset_ray_origin(sp, glm::dot(ng, to_light) > Scalar(0) ? ng : -ng), light_position);
      counts.shadow++;
      if (isect_.occluded(shadow)) continue;
      color += nff_direct(s, Vec3(ns), Vec3(-d), Vec3(glm::normalize(to_light)),
                          intensity_ * light.color);
    }

    if (depth >= kSpdMaxDepth) return color;
    if (s.ks > 0.0f || transmits) {
      const V r = reflect(d, ns);
      R reflected;
      reflected.org = offset_ray_origin(sp, glm::dot(r, ng) >= Scalar(0) ? ng : -ng);
      reflected.dir = r;
      counts.reflection++;
      const Color rc = trace(reflected, depth + 1, counts);
      color += s.ks * rc;
    }
    if (transmits) {
      const Scalar eta = entering ? Scalar(1) / Scalar(s.ior) : Scalar(s.ior);
      // refract() needs a normal against the ray; an interpolated one may not be.
      const V n_against = glm::dot(ns, d) < Scalar(0) ? ns : ng;
      V t;
      if (refract(d, n_against, eta, t)) {
        R refracted;
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
                        const RenderOptions& options, const nlohmann::json& params) {
  std::vector<NffSurface> surfaces;
  surfaces.reserve(scene.materials.size());
  for (const Material& m : scene.materials) surfaces.push_back(nff_surface(m));
  return render_frame_at(precision_of(params), scene, accel, options, FilmSampling::PixelCorners,
                         [&scene, &surfaces](const auto& isect) {
                           return SpdTracer<std::decay_t<decltype(isect)>>(scene, isect, surfaces);
                         });
}

nlohmann::json spd_params(const nlohmann::json& given) { return precision_params("spd", given); }

}  // namespace

const Integrator& spd_integrator() {
  static constexpr Integrator kSpd{
      "spd",
      "Eric Haines' SPD test rules: eye rays at pixel corners, tree depth 5, NFF shading",
      spd_params, render_spd};
  return kSpd;
}

}  // namespace tracer
