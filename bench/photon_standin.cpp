#include "photon_standin.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace bench_photon {

namespace {

using photon::Color;
using photon::Vec3;

struct Sphere {
  Vec3 centre;
  float radius;
};
constexpr Sphere kSpheres[] = {{{0.30f, 0.18f, 0.35f}, 0.18f}, {{0.72f, 0.18f, 0.62f}, 0.18f}};
const Vec3 kLight(0.5f, 0.95f, 0.45f);
constexpr float kSurvival = 0.7f;

struct Hit {
  float t = std::numeric_limits<float>::infinity();
  Vec3 normal{0.0f};  ///< Facing the ray's origin.
  Color albedo{0.7f};
};

/// Closest hit of the ray o + t d (t > 1e-5) with the box's five walls and the spheres.
Hit intersect(const Vec3& o, const Vec3& d) {
  Hit h;
  // Walls: x = 0 (red), x = 1 (green), y = 0, y = 1, z = 0; the box is open at z = 1.
  const struct {
    int axis;
    float at;
    Color albedo;
  } walls[] = {{0, 0.0f, {0.63f, 0.06f, 0.05f}}, {0, 1.0f, {0.14f, 0.45f, 0.09f}},
               {1, 0.0f, Color(0.7f)},           {1, 1.0f, Color(0.7f)},
               {2, 0.0f, Color(0.7f)}};
  for (const auto& w : walls) {
    if (d[w.axis] == 0.0f) continue;
    const float t = (w.at - o[w.axis]) / d[w.axis];
    if (!(t > 1e-5f && t < h.t)) continue;
    const Vec3 p = o + t * d;
    bool inside = true;
    for (int a = 0; a < 3; ++a)
      if (a != w.axis && (p[a] < 0.0f || p[a] > 1.0f)) inside = false;
    if (!inside) continue;
    h.t = t;
    h.normal = Vec3(0.0f);
    h.normal[w.axis] = d[w.axis] > 0.0f ? -1.0f : 1.0f;
    h.albedo = w.albedo;
  }
  for (const Sphere& s : kSpheres) {
    const Vec3 f = o - s.centre;
    const float b = glm::dot(f, d), c = glm::dot(f, f) - s.radius * s.radius;
    const float disc = b * b - c;
    if (disc < 0.0f) continue;
    const float root = std::sqrt(disc);
    for (const float t : {-b - root, -b + root}) {
      if (t > 1e-5f && t < h.t) {
        h.t = t;
        h.normal = glm::normalize(o + t * d - s.centre);
        if (glm::dot(h.normal, d) > 0.0f) h.normal = -h.normal;
        h.albedo = Color(0.7f);
        break;
      }
    }
  }
  return h;
}

Vec3 uniform_sphere(std::mt19937_64& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float z = 1.0f - 2.0f * u(rng), phi = 2.0f * std::numbers::pi_v<float> * u(rng);
  const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {s * std::cos(phi), s * std::sin(phi), z};
}

Vec3 cosine_hemisphere(const Vec3& n, std::mt19937_64& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float r = std::sqrt(u(rng)), phi = 2.0f * std::numbers::pi_v<float> * u(rng);
  const Vec3 a = std::abs(n.x) > 0.5f ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
  const Vec3 t = glm::normalize(glm::cross(a, n)), b = glm::cross(n, t);
  return glm::normalize(r * std::cos(phi) * t + r * std::sin(phi) * b +
                        std::sqrt(std::max(0.0f, 1.0f - r * r)) * n);
}

}  // namespace

PhotonBenchSet cornell_standin(std::size_t n, int grid, std::uint64_t seed) {
  PhotonBenchSet set;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  set.photons.reserve(n);
  // Light power 100 W; each emitted photon carries 100 W / (expected emissions), fixed up front
  // as 100 W / n: the absolute scale does not matter to a kNN search.
  const Color start_power(100.0f / float(n > 0 ? n : 1));
  while (set.photons.size() < n) {
    Vec3 o = kLight, d = uniform_sphere(rng);
    Color power = start_power;
    for (int bounce = 0; bounce < 32 && set.photons.size() < n; ++bounce) {
      const Hit h = intersect(o, d);
      if (!std::isfinite(h.t)) break;  // out through the open front
      const Vec3 p = o + h.t * d;
      set.photons.push_back(photon::Photon::make(p, power, d));
      if (u(rng) >= kSurvival) break;
      power *= h.albedo / kSurvival;
      o = p + 1e-4f * h.normal;
      d = cosine_hemisphere(h.normal, rng);
    }
  }
  const Vec3 eye(0.5f, 0.5f, 2.2f);
  const float half = std::tan(0.5f * 40.0f * std::numbers::pi_v<float> / 180.0f);
  for (int y = 0; y < grid; ++y) {
    for (int x = 0; x < grid; ++x) {
      const float sx = (2.0f * (x + 0.5f) / grid - 1.0f) * half;
      const float sy = (1.0f - 2.0f * (y + 0.5f) / grid) * half;
      const Vec3 d = glm::normalize(Vec3(sx, sy, -1.0f));
      const Hit h = intersect(eye, d);
      if (!std::isfinite(h.t)) continue;
      set.queries.push_back({eye + h.t * d, h.normal});
    }
  }
  return set;
}

}  // namespace bench_photon
