#pragma once
// Whitted-style recursive ray tracing: point lights with shadow rays, diffuse + Phong, mirrors,
// and dielectrics that split every ray into a reflected and a refracted one weighted by the
// Fresnel R and T, with Beer-Lambert absorption inside. Templated on the intersector, so each
// acceleration structure gets its own compiled copy of the whole recursion.
//
// What happens at a diffuse surface, and what an escaping ray sees, is the Shading policy:
// DirectLighting (Whitted's own: direct light through shadow rays, the background) or another
// integrator's (photon mapping adds caustics and indirect light), which then reuses the
// specular recursion unchanged.

#include "offset_ray.h"
#include "optics.h"
#include "ray_counts.h"
#include "scene.h"
#include "surface.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace tracer {

/// Largest channel of a path's throughput: the weight compared against min_weight.
inline float path_weight(const Color& throughput) {
  return std::max(throughput.x, std::max(throughput.y, throughput.z));
}

/// Beer-Lambert transmittance exp(-absorption * distance), per channel; a zero coefficient
/// transmits fully even over an infinite distance (no 0 * inf).
Color beer_transmittance(const Color& absorption, float distance);

/// Light arriving at p from one point light, unoccluded, before the BRDF: the radiant intensity
/// power / (4 pi) times the light's colour, times cos / distance^2. `to_light` = light - p.
Color point_light_irradiance(const PointLight& light, const Vec3& to_light, const Vec3& normal);

/// Surface response to direct light: a Lambertian albedo and a normalised Phong highlight.
struct DirectResponse {
  Color albedo{0.0f};      ///< Lambertian reflectance in [0, 1].
  float specular = 0.0f;   ///< Weight of the highlight; 0 = none.
  float shininess = 1.0f;  ///< Phong exponent.
};

/// The BRDF albedo / pi + specular (s + 2) / (2 pi) cos^s(alpha), where alpha lies between the
/// light direction mirrored about n and the direction to the eye (all unit vectors).
Color diffuse_phong_brdf(const DirectResponse& r, const Vec3& n, const Vec3& to_light_unit,
                         const Vec3& to_eye_unit);

/// A diffuse surface met by a path, as the Shading policy sees it (Scalar: the tracer's).
template <class Scalar>
struct DiffuseHitT {
  const SurfacePointT<Scalar>& sp;  ///< The point, with its error bound (rays leave through it).
  Vec3T<Scalar> n{0};               ///< Unit shading normal, turned to the side the ray arrived from.
  Vec3T<Scalar> n_geo{0};           ///< Unit geometric normal, on that side too.
  Vec3T<Scalar> to_eye{0};          ///< Unit direction back along the arriving ray.
  DirectResponse response;          ///< Lambertian albedo and Phong highlight.
};
using DiffuseHit = DiffuseHitT<float>;

/// Where a ray of the recursion is, for the Shading policy.
struct PathState {
  int depth = 1;                ///< Recursion depth of the ray (camera ray = 1).
  Color throughput{1.0f};       ///< Path weight at this surface (attenuation included).
  Color absorption{0.0f};       ///< Beer coefficient of the medium the ray arrived through.
  int gathers = 0;              ///< Diffuse bounces sampled on the path so far (0: camera path).
};

/// Whitted's own shading: direct light through shadow rays at diffuse surfaces; a ray that
/// escapes sees the background.
struct DirectLighting {
  template <class Tracer, class Hit>
  Color diffuse(const Tracer& tracer, const Hit& h, const PathState&, RayCounts& counts) const {
    return tracer.direct(h.sp, h.n, h.n_geo, h.to_eye, h.response, counts);
  }
  Color escaped(const Scene& scene, const PathState&) const { return scene.background; }
};

template <class Isect, class Shading = DirectLighting>
class Whitted {
 public:
  using Scalar = typename Isect::Scalar;  ///< float, or double for the naive reference.
  using V = Vec3T<Scalar>;
  using R = RayT<Scalar>;
  using Point = SurfacePointT<Scalar>;

  /// An integrator over `scene` (which must outlive it) querying geometry through `isect`, with
  /// the scene's recursion limits or `limits` in their place, shading diffuse surfaces by
  /// `shading`.
  Whitted(const Scene& scene, const Isect& isect) : Whitted(scene, isect, scene.render) {}
  Whitted(const Scene& scene, const Isect& isect, const RenderSettings& limits, Shading shading = {})
      : scene_(&scene), isect_(isect), limits_(limits), shading_(std::move(shading)) {}

  /// Radiance arriving along a camera ray (unit direction); counts every ray traced.
  Color trace_eye(const R& ray, RayCounts& counts) const {
    counts.eye++;
    return trace(ray, 1, Color(1.0f), Color(0.0f), counts);
  }

  /// trace_eye for a camera ray whose closest hit `hit` the caller has already found (a packet
  /// of camera rays, render_frame.h): the same radiance, the same counts.
  Color trace_eye_hit(const R& ray, const HitT<Scalar>& hit, RayCounts& counts) const {
    counts.eye++;
    return shade(ray, hit, 1, Color(1.0f), Color(0.0f), counts, 0);
  }

  /// Radiance along `ray` at recursion depth `depth` (camera ray = 1). `throughput` is the
  /// path's weight before this ray and `absorption` the Beer coefficient of the medium it
  /// travels in; `gathers` counts the diffuse bounces sampled before it (PathState). Geometry is
  /// computed in Scalar, colours in float.
  Color trace(const R& ray, int depth, const Color& throughput, const Color& absorption,
              RayCounts& counts, int gathers = 0) const {
    return shade(ray, isect_.closest(ray), depth, throughput, absorption, counts, gathers);
  }

 private:
  /// trace() from the ray's closest hit on.
  Color shade(const R& ray, const HitT<Scalar>& hit, int depth, const Color& throughput,
              const Color& absorption, RayCounts& counts, int gathers) const {
    if (!hit.found())
      return beer_transmittance(absorption, accel::kInfinity) *
             shading_.escaped(*scene_, PathState{depth, throughput, absorption, gathers});
    if (depth == 1) counts.eye_hits++;

    const Color attenuation = beer_transmittance(absorption, float(hit.t));
    const Color weight = throughput * attenuation;
    const Point sp = surface_point(isect_.geometry(), ray, hit, isect_.triangle_test());
    const Material& m = scene_->materials[sp.material];
    // Normals turned to the side the ray arrives from.
    const bool front = glm::dot(ray.dir, sp.n_geo) <= Scalar(0);
    const V n_geo = front ? sp.n_geo : -sp.n_geo;
    V n = front ? sp.n_shade : -sp.n_shade;
    if (glm::dot(n, n_geo) < Scalar(0)) n = n_geo;  // interpolated normal turned past the surface
    const PathState path{depth, weight, absorption, gathers};

    Color radiance(0.0f);
    switch (m.type) {
      case MaterialType::Diffuse:
        radiance = shading_.diffuse(
            *this,
            DiffuseHitT<Scalar>{sp, n, n_geo, -ray.dir, {m.albedo, m.specular, m.shininess}},
            path, counts);
        break;
      case MaterialType::Mirror:
        radiance = spawn(sp, n_geo, reflect(ray.dir, n), depth, weight * m.reflectance,
                         absorption, counts.reflection, counts, gathers) *
                   m.reflectance;
        break;
      case MaterialType::Dielectric:
        radiance =
            dielectric(ray.dir, sp, n, n_geo, front, m, m.ior, depth, weight, absorption, counts,
                       gathers);
        break;
      case MaterialType::Nff: {
        // The classic NFF surface: kd-scaled diffuse + ks-weighted highlight from the lights,
        // a mirror ray weighted ks, and a refracted ray weighted by the transmittance.
        radiance = shading_.diffuse(
            *this,
            DiffuseHitT<Scalar>{sp, n, n_geo, -ray.dir, {m.kd * m.albedo, m.ks, m.shininess}},
            path, counts);
        if (m.ks > 0.0f)
          radiance += m.ks * spawn(sp, n_geo, reflect(ray.dir, n), depth, weight * m.ks,
                                   absorption, counts.reflection, counts, gathers);
        if (m.transmittance > 0.0f) {
          const Scalar ior = m.ior > 0.0f ? m.ior : 1.0f;
          const auto s = orient(ray.dir, front ? n : -n, ior);
          V t;
          if (refract(ray.dir, s.normal, s.eta_i / s.eta_t, t))
            radiance += m.transmittance * spawn(sp, -n_geo, glm::normalize(t), depth,
                                                weight * m.transmittance, absorption,
                                                counts.refraction, counts, gathers);
        }
        break;
      }
    }
    return attenuation * radiance;
  }

 public:
  /// Traces a secondary ray of direction `dir` from the surface point sp, leaving on the side of
  /// `side` (a unit geometric normal), when the depth and weight limits allow; counts it.
  Color spawn(const Point& sp, const V& side, const V& dir, int depth, const Color& weight,
              const Color& absorption, std::uint64_t& kind_count, RayCounts& counts,
              int gathers = 0) const {
    const RenderSettings& rs = limits_;
    if (depth + 1 > rs.max_depth || !(path_weight(weight) >= rs.min_weight)) return Color(0.0f);
    R r;
    r.org = offset_ray_origin(sp, side);
    r.dir = dir;
    kind_count++;
    return trace(r, depth + 1, weight, absorption, counts, gathers);
  }

  /// Both Fresnel branches of a smooth dielectric. `n`, `n_geo` face the arriving ray.
  Color dielectric(const V& d, const Point& sp, const V& n, const V& n_geo, bool front,
                   const Material& m, Scalar ior, int depth, const Color& weight,
                   const Color& absorption, RayCounts& counts, int gathers) const {
    // The sign of d.n_outward says whether the ray enters or leaves; leaving uses
    // eta = ior / 1. The medium beyond the surface is air unless the ray enters.
    const auto s = orient(d, front ? n : -n, ior);
    const Color inside_absorption = m.absorption;
    const Color beyond = s.entering ? inside_absorption : Color(0.0f);
    const Color here = absorption;
    V t;
    float reflectance = 1.0f;
    const bool transmits = refract(d, s.normal, s.eta_i / s.eta_t, t);
    if (transmits) reflectance = float(fresnel_dielectric(s.cos_i, s.eta_i, s.eta_t));
    Color radiance(0.0f);
    if (reflectance > 0.0f)
      radiance += reflectance * spawn(sp, n_geo, reflect(d, n), depth, weight * reflectance, here,
                                      counts.reflection, counts, gathers);
    if (transmits && reflectance < 1.0f) {
      const float tr = 1.0f - reflectance;
      radiance += tr * spawn(sp, -n_geo, glm::normalize(t), depth, weight * tr, beyond,
                             counts.refraction, counts, gathers);
    }
    return radiance;
  }

  /// Direct light from every point light through shadow rays, diffuse + Phong. `n` and `n_geo`
  /// face the arriving ray; shadow rays leave on n_geo's side.
  Color direct(const Point& sp, const V& n, const V& n_geo, const V& to_eye,
               const DirectResponse& response, RayCounts& counts) const {
    Color radiance(0.0f);
    const V origin = offset_ray_origin(sp, n_geo);
    for (const PointLight& light : scene_->lights) {
      const V light_position(light.position);
      const V to_light = light_position - sp.p;
      if (!(glm::dot(to_light, n) > Scalar(0)) || !(glm::dot(to_light, n_geo) > Scalar(0))) continue;
      const R shadow = segment_to(origin, light_position);  // t = 1 just short of the light
      counts.shadow++;
      if (isect_.occluded(shadow)) continue;
      const V l = glm::normalize(to_light);
      radiance += diffuse_phong_brdf(response, Vec3(n), Vec3(l), Vec3(to_eye)) *
                  point_light_irradiance(light, Vec3(to_light), Vec3(n));
    }
    return radiance;
  }

  const Scene& scene() const { return *scene_; }
  const Isect& intersector() const { return isect_; }

 private:
  const Scene* scene_;
  Isect isect_;
  RenderSettings limits_;
  Shading shading_;
};

}  // namespace tracer
