#pragma once
// One photon path through the scene (the paper's §4), a template on the intersector so that each
// acceleration structure's loop is compiled on its own:
//   - mirror: reflect, surviving with probability max(reflectance), the power scaled by
//     reflectance / max(reflectance);
//   - dielectric: reflect with probability R (Fresnel, tracer/optics.h), else refract (a Russian
//     roulette on R and T = 1 - R, power unchanged); Beer-Lambert absorption scales the power
//     inside;
//   - diffuse: the photon may be stored (see below), then survives with probability
//     max(albedo), its power scaled by albedo / max(albedo), and leaves in a cosine-distributed
//     direction about the shading normal. A Phong highlight (Material::specular) is not
//     scattered: photons see the Lambertian albedo only (the highlight is direct light).
//   - NFF surfaces: one roulette over diffuse (kd * colour), mirror (ks) and refraction (T, no
//     Fresnel, as the NFF model has it), with probabilities scaled down together when they sum
//     above 1 (the NFF model is not energy-conserving; the weights keep its expectation).
// Stores: the global pass keeps every diffuse hit after the path's first diffuse bounce (the
// first diffuse hit is direct light, or a caustic, both computed otherwise); the caustic pass
// keeps the first diffuse hit after at least one specular bounce and ends the path there.
// Secondary rays leave from tracer's offset_ray_origin, like every secondary ray of the tracer.

#include "emission.h"
#include "photon_rng.h"

#include "tracer/intersector.h"
#include "tracer/offset_ray.h"
#include "tracer/optics.h"
#include "tracer/scene.h"
#include "tracer/surface.h"
#include "tracer/whitted.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace photon {

/// A photon stored by the tracer, before its power is known (that needs the count of photons
/// each light emitted in the end).
struct TracedPhoton {
  Vec3 position{0.0f};   ///< Where it was stored, world units.
  Vec3 direction{0.0f};  ///< Unit direction of travel when it arrived.
  Color weight{1.0f};    ///< Throughput since emission (the roulettes' colour changes).
  std::uint32_t light = 0;  ///< Emitting light, index into Emission::lights().
  std::uint32_t path = 0;   ///< Index of its photon path within the tracing round.
};

/// Work of one worker's photon paths.
struct PathCounters {
  std::uint64_t rays = 0;          ///< Photon rays traced.
  std::uint64_t diffuse_hits = 0;  ///< Hits on surfaces with a diffuse part.
};

/// A unit direction about the unit normal n, cosine-distributed, from two uniforms in [0, 1).
inline Vec3 cosine_direction(const Vec3& n, float u1, float u2) {
  const float r = std::sqrt(u1);
  const float phi = 2.0f * std::numbers::pi_v<float> * u2;
  Vec3 t, b;
  orthonormal_basis(n, t, b);
  return (r * std::cos(phi)) * t + (r * std::sin(phi)) * b + std::sqrt(std::max(0.0f, 1.0f - u1)) * n;
}

template <class Isect>
class PhotonPathTracer {
 public:
  PhotonPathTracer(const tracer::Scene& scene, const Isect& isect, PhotonPass pass, int max_depth)
      : scene_(&scene), isect_(isect), pass_(pass), max_depth_(max_depth) {}

  /// Traces the photon path leaving along `ray` from emitting light `light`, drawing from
  /// `rng`; appends the photons it stores to `out`, tagged with `path`.
  void trace(accel::Ray ray, PhotonRng& rng, std::uint32_t light, std::uint32_t path,
             std::vector<TracedPhoton>& out, PathCounters& counters) const {
    using tracer::MaterialType;
    Color weight(1.0f);
    Color absorption(0.0f);  // Beer coefficient of the medium the photon travels in
    int diffuse_bounces = 0, specular_bounces = 0;
    for (int interaction = 0; interaction < max_depth_; ++interaction) {
      counters.rays++;
      const tracer::Hit hit = isect_.closest(ray);
      if (!hit.found()) return;
      weight *= tracer::beer_transmittance(absorption, hit.t);
      const tracer::SurfacePoint sp = tracer::surface_point(isect_.geometry(), ray, hit, isect_.triangle_test());
      const tracer::Material& m = scene_->materials[sp.material];
      const Vec3 d = glm::normalize(ray.dir);
      // Normals turned to the side the photon arrives from (as the Whitted integrator does).
      const bool front = glm::dot(ray.dir, sp.n_geo) <= 0.0f;
      const Vec3 n_geo = front ? sp.n_geo : -sp.n_geo;
      Vec3 n = front ? sp.n_shade : -sp.n_shade;
      if (glm::dot(n, n_geo) < 0.0f) n = n_geo;

      // The surface's parts: diffuse albedo, mirror colour, transmission, and their roulette.
      Color diffuse(0.0f), mirror(0.0f);
      float transmit = 0.0f, ior = 1.0f;
      bool has_diffuse = false, fresnel = false;
      switch (m.type) {
        case MaterialType::Diffuse:
          has_diffuse = true;
          diffuse = m.albedo;
          break;
        case MaterialType::Mirror:
          mirror = m.reflectance;
          break;
        case MaterialType::Dielectric:
          fresnel = true;
          ior = m.ior;
          break;
        case MaterialType::Nff:
          has_diffuse = true;
          diffuse = m.kd * m.albedo;
          mirror = Color(m.ks);
          transmit = m.transmittance;
          ior = m.ior > 0.0f ? m.ior : 1.0f;
          break;
      }

      if (has_diffuse) {
        counters.diffuse_hits++;
        const bool store = pass_ == PhotonPass::Global
                               ? diffuse_bounces > 0
                               : specular_bounces > 0 && diffuse_bounces == 0;
        if (store) out.push_back({sp.p, d, weight, light, path});
        if (pass_ == PhotonPass::Caustic && m.type == MaterialType::Diffuse) return;
      }

      // Refraction geometry (dielectric and NFF T): the interface seen from the photon's side.
      const tracer::Interface s = tracer::orient(d, front ? n : -n, ior);
      Vec3 refracted(0.0f);
      const bool can_refract =
          (fresnel || transmit > 0.0f) && tracer::refract(d, s.normal, s.eta_i / s.eta_t, refracted);
      if (fresnel) {
        const float r = can_refract ? tracer::fresnel_dielectric(s.cos_i, s.eta_i, s.eta_t) : 1.0f;
        mirror = Color(r);  // the roulette's probabilities are R and T = 1 - R: the weight stays
        transmit = 1.0f - r;
      }
      if (!can_refract) transmit = 0.0f;

      float p_diffuse = std::max(diffuse.x, std::max(diffuse.y, diffuse.z));
      float p_mirror = std::max(mirror.x, std::max(mirror.y, mirror.z));
      float p_transmit = transmit;
      const float sum = p_diffuse + p_mirror + p_transmit;
      if (sum > 1.0f) {
        p_diffuse /= sum;
        p_mirror /= sum;
        p_transmit /= sum;
      }
      const float u = rng.uniform();
      accel::Ray next;
      if (u < p_diffuse) {
        if (pass_ == PhotonPass::Caustic) return;  // LS+D ends at its diffuse surface
        const float u1 = rng.uniform(), u2 = rng.uniform();
        const Vec3 dir = cosine_direction(n, u1, u2);
        if (!(glm::dot(dir, n_geo) > 0.0f)) return;  // an interpolated normal led below the surface
        weight *= diffuse / p_diffuse;
        next.org = tracer::offset_ray_origin(sp, n_geo);
        next.dir = dir;
        ++diffuse_bounces;
      } else if (u < p_diffuse + p_mirror) {
        weight *= mirror / p_mirror;
        next.org = tracer::offset_ray_origin(sp, n_geo);
        next.dir = tracer::reflect(d, n);
        ++specular_bounces;
      } else if (u < p_diffuse + p_mirror + p_transmit) {
        weight *= transmit / p_transmit;
        if (fresnel) absorption = s.entering ? m.absorption : Color(0.0f);
        next.org = tracer::offset_ray_origin(sp, -n_geo);
        next.dir = glm::normalize(refracted);
        ++specular_bounces;
      } else {
        return;  // absorbed
      }
      ray = next;
    }
  }

 private:
  const tracer::Scene* scene_;
  Isect isect_;
  PhotonPass pass_;
  int max_depth_;
};

}  // namespace photon
