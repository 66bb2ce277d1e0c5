#include "bench_rays.h"

#include "tracer/camera.h"
#include "tracer/offset_ray.h"
#include "tracer/surface.h"

#include <random>

namespace bench {

using accel::Ray;
using accel::Vec3;
using tracer::Hit;

std::vector<Ray> camera_rays(const tracer::Scene& scene, int width, int height) {
  const tracer::PinholeCamera camera(scene.camera, width, height);
  std::vector<Ray> rays;
  rays.reserve(std::size_t(width) * std::size_t(height));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) rays.push_back(camera.primary_ray(x, y));
  return rays;
}

std::vector<Ray> spawned_rays(const tracer::Geometry& g, const std::vector<Ray>& primary,
                              const std::vector<Hit>& hits) {
  std::mt19937 rng(2024);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  std::vector<Ray> out;
  std::size_t k = 0;
  for (std::size_t i = 0; i < primary.size(); ++i) {
    if (!hits[i].found() || hits[i].is_plane()) continue;
    const Ray& r = primary[i];
    const tracer::SurfacePoint sp = tracer::surface_point(g, r, hits[i], tracer::TriangleTest::Watertight);
    const Vec3 n = sp.n_geo;
    Vec3 d;
    if (k++ % 2 == 0) {
      d = r.dir - 2.0f * glm::dot(r.dir, n) * n;
    } else {
      // z, y, x, sequenced: as gcc evaluated Vec3(gauss(rng), gauss(rng), gauss(rng)), whose
      // argument order C++ leaves unspecified (clang drew other rays from it).
      const float gz = gauss(rng), gy = gauss(rng), gx = gauss(rng);
      d = glm::normalize(Vec3(gx, gy, gz));
      if (glm::dot(d, n) < 0.0f) d = -d;
    }
    out.push_back(tracer::spawn_ray(sp, d));
  }
  return out;
}

std::vector<Ray> shadow_rays(const tracer::Scene& scene, const std::vector<Ray>& primary, const std::vector<Hit>& hits) {
  const tracer::Geometry& g = scene.geometry;
  std::vector<Ray> out;
  for (std::size_t i = 0; i < primary.size(); ++i) {
    if (!hits[i].found() || hits[i].is_plane()) continue;
    const tracer::SurfacePoint sp = tracer::surface_point(g, primary[i], hits[i], tracer::TriangleTest::Watertight);
    const Vec3 n = glm::dot(sp.n_geo, primary[i].dir) > 0.0f ? -sp.n_geo : sp.n_geo;
    const Vec3 origin = tracer::offset_ray_origin(sp, n);
    for (const tracer::PointLight& light : scene.lights)
      if (glm::dot(light.position - sp.p, n) > 0.0f) out.push_back(tracer::segment_to(origin, light.position));
  }
  return out;
}

}  // namespace bench
