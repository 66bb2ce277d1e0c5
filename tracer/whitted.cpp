#include "whitted.h"

#include "render_frame.h"
#include "whitted_params.h"

namespace tracer {

namespace {
constexpr float kPi = 3.14159265358979f;
}

Color beer_transmittance(const Color& absorption, float distance) {
  Color out(1.0f);
  for (int c = 0; c < 3; ++c)
    if (absorption[c] > 0.0f) out[c] = std::exp(-absorption[c] * distance);
  return out;
}

Color point_light_irradiance(const PointLight& light, const Vec3& to_light, const Vec3& normal) {
  const float d2 = glm::dot(to_light, to_light);
  const float cos_theta = glm::dot(normal, to_light) / std::sqrt(d2);
  const float intensity = light.power_w / (4.0f * kPi);  // W/sr, emitted uniformly
  return light.color * (intensity * std::max(cos_theta, 0.0f) / d2);
}

Color diffuse_phong_brdf(const DirectResponse& r, const Vec3& n, const Vec3& to_light_unit,
                         const Vec3& to_eye_unit) {
  Color f = r.albedo / kPi;
  if (r.specular > 0.0f) {
    const Vec3 mirrored = reflect(-to_light_unit, n);
    const float c = std::max(glm::dot(mirrored, to_eye_unit), 0.0f);
    f += Color(r.specular * (r.shininess + 2.0f) / (2.0f * kPi) * std::pow(c, r.shininess));
  }
  return f;
}

namespace {

RenderResult render_whitted(const Scene& scene, const accel::AnyAccel& accel,
                            const RenderOptions& options, const nlohmann::json& knobs) {
  const WhittedParams p = WhittedParams::knobs().from_json(knobs);
  const RenderSettings limits = p.limits(scene);
  const int spp = p.samples_per_pixel(scene);
  RenderOptions o = options;
  o.triangle_test = p.triangle;
  RenderResult r = render_frame_at(p.precision, scene, accel, o,
                                   FilmSpec(FilmSampling::PixelSamples, spp, p.seed),
                                   [&scene, &limits](const auto& isect) {
                                     return Whitted<std::decay_t<decltype(isect)>>(scene, isect,
                                                                                   limits);
                                   });
  // The settings in effect, the scene's where no knob was given.
  WhittedParams effective = p;
  effective.max_depth = limits.max_depth;
  effective.min_weight = limits.min_weight;
  effective.spp = spp;
  r.stats["effective"] = WhittedParams::knobs().to_json(effective);
  return r;
}

const knobs::AnyKnobTable& whitted_knobs() { return WhittedParams::knobs(); }

}  // namespace

const Integrator& whitted_integrator() {
  static constexpr Integrator kWhitted{
      "whitted",
      "Whitted ray tracing: point lights with shadow rays, diffuse + Phong, mirrors, Fresnel "
      "dielectrics",
      whitted_knobs, render_whitted};
  return kWhitted;
}

}  // namespace tracer
