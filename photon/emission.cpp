#include "emission.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>

namespace photon {

double light_share_power(const tracer::PointLight& light) {
  const double mean = (double(light.color.x) + double(light.color.y) + double(light.color.z)) / 3.0;
  return light.power_w > 0.0f && mean > 0.0 ? double(light.power_w) * mean : 0.0;
}

LightSequence::LightSequence(std::vector<double> powers) : counts_(powers.size(), 0) {
  double total = 0.0;
  for (double p : powers) total += p;
  share_.reserve(powers.size());
  for (double p : powers) share_.push_back(total > 0.0 ? p / total : 0.0);
}

std::uint32_t LightSequence::next() {
  ++emitted_;
  const double n = double(emitted_);
  std::uint32_t best = 0;
  double best_lag = -1e300;
  for (std::uint32_t j = 0; j < share_.size(); ++j) {
    if (share_[j] <= 0.0) continue;
    const double lag = n * share_[j] - double(counts_[j]);
    if (lag > best_lag) {
      best_lag = lag;
      best = j;
    }
  }
  ++counts_[best];
  return best;
}

Emission::Emission(const tracer::Scene& scene, PhotonPass pass, bool uniform_fallback) {
  SpecularBounds spec = pass == PhotonPass::Caustic ? specular_bounds(scene) : SpecularBounds{};
  if (pass == PhotonPass::Caustic && !spec.all && spec.box.is_empty()) {
    if (!uniform_fallback) return;  // nothing to aim at
    spec.all = true;
  }
  const Vec3 centre = 0.5f * (spec.box.lo + spec.box.hi);
  const float radius = 0.5f * glm::length(spec.box.hi - spec.box.lo);
  for (const tracer::PointLight& l : scene.lights) {
    if (light_share_power(l) <= 0.0) continue;
    EmittingLight e;
    e.position = l.position;
    e.power = l.power_w * l.color;
    if (pass == PhotonPass::Caustic && !spec.all) {
      const Vec3 to_centre = centre - l.position;
      const float d = glm::length(to_centre);
      if (d > radius) {  // outside the sphere: the cone that holds it
        e.axis = to_centre / d;
        const double s = double(radius) / double(d);
        e.cos_max = float(std::sqrt(1.0 - s * s));
        // The fraction of the light's (isotropic) power that goes into the cone.
        e.power *= float((1.0 - double(e.cos_max)) / 2.0);
      }
    }
    lights_.push_back(e);
  }
}

LightSequence Emission::sequence() const {
  std::vector<double> powers;
  for (const EmittingLight& e : lights_)
    powers.push_back((double(e.power.x) + double(e.power.y) + double(e.power.z)) / 3.0);
  return LightSequence(std::move(powers));
}

accel::Ray Emission::emit(std::uint32_t l, float u1, float u2) const {
  const EmittingLight& e = lights_[l];
  const float cos_t = 1.0f - u1 * (1.0f - e.cos_max);
  const float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t));
  const float phi = 2.0f * std::numbers::pi_v<float> * u2;
  Vec3 t, b;
  orthonormal_basis(e.axis, t, b);
  accel::Ray ray;
  ray.org = e.position;
  ray.dir = (sin_t * std::cos(phi)) * t + (sin_t * std::sin(phi)) * b + cos_t * e.axis;
  return ray;
}

Color Emission::photon_power(std::uint32_t l, std::uint64_t n) const {
  return n > 0 ? lights_[l].power / float(n) : Color(0.0f);
}

}  // namespace photon
