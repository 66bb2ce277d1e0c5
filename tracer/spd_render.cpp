#include "spd_render.h"

#include "intersector.h"
#include "nff_shading.h"
#include "offset_ray.h"
#include "optics.h"
#include "render_frame.h"
#include "surface.h"

#include <algorithm>
#include <cstdint>
#include <span>
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

  /// trace_eye_hit for a packet of camera rays (up to 16) and their hits, into out[i]: the
  /// shadow rays of all their hits toward one light go out as one packet (occluded_packet),
  /// then each ray is shaded as shade() would, to the bit. Scenes of over 64 lights go ray by
  /// ray.
  void trace_eye_packet(std::span<const R> rays, std::span<const HitT<Scalar>> hits, RayCounts& counts,
                        std::span<Color> out) const {
    constexpr std::size_t kMax = 16;
    const std::size_t n = std::min(rays.size(), kMax);
    const std::vector<PointLight>& lights = scene_->lights;
    if (lights.size() > 64) {
      for (std::size_t i = 0; i < n; ++i) out[i] = trace_eye_hit(rays[i], hits[i], counts);
      return;
    }
    Shading h[kMax];
    std::uint64_t lit[kMax] = {};  // bit l: light l reaches the hit
    for (std::size_t i = 0; i < n; ++i) {
      counts.eye++;
      if (!hits[i].found()) continue;
      counts.eye_hits++;
      h[i] = shading(rays[i], hits[i]);
    }
    for (std::size_t l = 0; l < lights.size(); ++l) {
      R shadows[kMax];
      std::size_t lane[kMax], m = 0;
      const V light_position(lights[l].position);
      for (std::size_t i = 0; i < n; ++i) {
        if (!hits[i].found()) continue;
        const V to_light = light_position - h[i].sp.p;
        if (!faces(h[i], to_light)) continue;
        shadows[m] = shadow_ray(h[i], light_position, to_light);
        lane[m++] = i;
      }
      if (m == 0) continue;
      counts.shadow += m;
      const std::uint32_t occluded = isect_.occluded_packet(std::span<const R>(shadows, m));
      for (std::size_t k = 0; k < m; ++k)
        if (!((occluded >> k) & 1u)) lit[lane[k]] |= std::uint64_t(1) << l;
    }
    for (std::size_t i = 0; i < n; ++i)
      out[i] = hits[i].found() ? shade_lit(h[i], 1, counts, [&](std::size_t l, const V&, const V&) { return ((lit[i] >> l) & 1u) != 0; })
                               : scene_->background;
  }

  /// trace() from the ray's closest hit on.
  Color shade(const R& ray, const HitT<Scalar>& hit, int depth, RayCounts& counts) const {
    if (!hit.found()) return scene_->background;
    const Shading h = shading(ray, hit);
    return shade_lit(h, depth, counts, [&](std::size_t, const V& light_position, const V& to_light) {
      counts.shadow++;
      return !isect_.occluded(shadow_ray(h, light_position, to_light));
    });
  }

 private:
  /// What shading a hit needs before any ray leaves it.
  struct Shading {
    SurfacePointT<Scalar> sp;
    const NffSurface* s = nullptr;
    V d, ng, ns;          ///< Unit ray direction; geometric and shading normals facing the ray.
    bool entering = true;  ///< The ray enters the (transmitting) surface.
  };

  Shading shading(const R& ray, const HitT<Scalar>& hit) const {
    const Geometry& geo = isect_.geometry();
    Shading h;
    SurfacePointT<Scalar>& sp = h.sp;
    sp = surface_point(geo, ray, hit, isect_.triangle_test());
    // A sphere of negative radius shows its inside: its normal points inwards.
    if (!hit.is_plane() && geo.kind_of(hit.prim) == PrimitiveKind::Sphere &&
        geo.spheres[hit.prim].radius < 0.0f) {
      sp.n_geo = -sp.n_geo;
      sp.n_shade = -sp.n_shade;
    }
    // Vertex normals decide which side of a smooth triangle is its front.
    if (glm::dot(sp.n_geo, sp.n_shade) < Scalar(0)) sp.n_geo = -sp.n_geo;

    h.s = &(*surfaces_)[sp.material];
    h.d = glm::normalize(ray.dir);
    h.ng = sp.n_geo;
    h.ns = sp.n_shade;
    if (h.s->transmittance > 0.0f && glm::dot(h.ng, h.d) > Scalar(0)) {  // two-sided: face the arriving ray
      h.ng = -h.ng;
      h.ns = -h.ns;
      h.entering = false;
    }
    return h;
  }

  /// Whether the shading normal faces a light at `to_light` (= light - p; else no shadow ray).
  static bool faces(const Shading& h, const V& to_light) { return glm::dot(h.ns, to_light) > Scalar(0); }

  /// The shadow ray toward the light at `light_position` (`to_light` from the point): it leaves
  /// on the light's side; t = 1 just short of the light.
  static R shadow_ray(const Shading& h, const V& light_position, const V& to_light) {
    return segment_to(offset_ray_origin(h.sp, glm::dot(h.ng, to_light) > Scalar(0) ? h.ng : -h.ng), light_position);
  }

  /// The colour of a hit at tree depth `depth`; visible(l, light_position, to_light) says
  /// whether light l, which the normal faces, reaches it (and counts its shadow ray).
  template <class Visible>
  Color shade_lit(const Shading& h, int depth, RayCounts& counts, Visible&& visible) const {
    const NffSurface& s = *h.s;
    const SurfacePointT<Scalar>& sp = h.sp;
    const V d = h.d, ng = h.ng, ns = h.ns;
    const bool transmits = s.transmittance > 0.0f;

    Color color = nff_ambient(s, intensity_);
    for (std::size_t l = 0; l < scene_->lights.size(); ++l) {
      const PointLight& light = scene_->lights[l];
      const V light_position(light.position);
      const V to_light = light_position - sp.p;
      if (!faces(h, to_light) || !visible(l, light_position, to_light)) continue;
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
      const Scalar eta = h.entering ? Scalar(1) / Scalar(s.ior) : Scalar(s.ior);
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

  const Scene* scene_;
  Isect isect_;
  const std::vector<NffSurface>* surfaces_;
  float intensity_;
};

/// The SPD integrator's knobs.
struct SpdParams {
  Precision precision = Precision::Float;  ///< Arithmetic of the whole tracer.
  TriangleTest triangle = TriangleTest::Watertight;  ///< Ray/triangle routine.

  static const knobs::KnobTable<SpdParams>& knobs() {
    static const knobs::KnobTable<SpdParams> table(
        "spd", {precision_knob(&SpdParams::precision), triangle_knob(&SpdParams::triangle)});
    return table;
  }
};

RenderResult render_spd(const Scene& scene, const accel::AnyAccel& accel,
                        const RenderOptions& options, const nlohmann::json& params) {
  std::vector<NffSurface> surfaces;
  surfaces.reserve(scene.materials.size());
  for (const Material& m : scene.materials) surfaces.push_back(nff_surface(m));
  const SpdParams p = SpdParams::knobs().from_json(params);
  RenderOptions o = options;
  o.triangle_test = p.triangle;
  return render_frame_at(p.precision, scene, accel, o, FilmSampling::PixelCorners,
                         [&scene, &surfaces](const auto& isect) {
                           return SpdTracer<std::decay_t<decltype(isect)>>(scene, isect, surfaces);
                         });
}

const knobs::AnyKnobTable& spd_knobs() { return SpdParams::knobs(); }

}  // namespace

const Integrator& spd_integrator() {
  static constexpr Integrator kSpd{
      "spd",
      "Eric Haines' SPD test rules: eye rays at pixel corners, tree depth 5, NFF shading",
      spd_knobs, render_spd};
  return kSpd;
}

}  // namespace tracer
