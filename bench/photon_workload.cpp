#include "photon_workload.h"

#include "photon/map_needs.h"
#include "photon/photon_params.h"
#include "photon/photon_tracing.h"

#include "scenes_gen/generators.h"

#include "tracer/camera.h"
#include "tracer/intersector.h"
#include "tracer/surface.h"

#include "accel/accel.h"

#include <glm/geometric.hpp>

namespace bench {

PhotonWorkload cornell_photon_workload(std::size_t n_photons, int width, int height,
                                       std::uint64_t seed) {
  const tracer::Scene scene = scenes_gen::generate("cornell", {});
  const std::vector<accel::Aabb> boxes = scene.geometry.primitive_bounds();
  const accel::AnyAccel structure = accel::make_accel("bvh", nlohmann::json::object(), boxes);

  photon::PassOptions o;
  o.pass = photon::PhotonPass::Global;
  o.target = n_photons;
  o.max_depth = photon::PhotonParams{}.max_photon_depth;
  o.seed = seed;
  photon::PassResult pass = photon::trace_photon_pass(scene, structure, o);
  PhotonWorkload w;
  w.photons = std::move(pass.photons);
  w.emitted = pass.emitted;

  const tracer::PinholeCamera camera(scene.camera, width, height);
  tracer::with_intersector<false>(scene.geometry, structure, tracer::TriangleTest::Watertight, [&](const auto& isect) {
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const accel::Ray ray = camera.primary_ray(x, y);
        const tracer::Hit hit = isect.closest(ray);
        if (!hit.found()) continue;
        const tracer::SurfacePoint sp = tracer::surface_point(scene.geometry, ray, hit, tracer::TriangleTest::Watertight);
        const photon::MaterialRole role = photon::role_of(scene.materials[sp.material]);
        if (!role.diffuse || role.specular) continue;
        const photon::Vec3 n = glm::dot(ray.dir, sp.n_shade) <= 0.0f ? sp.n_shade : -sp.n_shade;
        w.queries.push_back({sp.p, n});
      }
  });
  return w;
}

}  // namespace bench
