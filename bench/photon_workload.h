#pragma once
// Photons and queries for the kNN benchmarks (bench/bench_photon.cpp): the Cornell box's global
// map, and the diffuse points its camera rays hit, where the renderer would gather.

#include "photon/photon.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace bench {

/// One gather position: a diffuse surface point seen by the camera.
struct PhotonQuery {
  photon::Vec3 position{0.0f};  ///< World units.
  photon::Vec3 normal{0.0f};    ///< Unit shading normal, turned towards the camera.
};

struct PhotonWorkload {
  std::vector<photon::Photon> photons;  ///< The global map's photons, in path order.
  std::vector<PhotonQuery> queries;     ///< In pixel order (row by row).
  std::uint64_t emitted = 0;            ///< Photon paths it took.
};

/// `n_photons` (>= 1) photons of the Cornell box's global map (scenes_gen "cornell", the photon
/// integrator's global pass with its defaults and `seed`, traced on every core through a BVH:
/// bit-identical for any thread count), and the first hits of a `width` x `height` grid of
/// camera rays (pixel centres) that land on a diffuse surface (hits on the mirror and glass
/// spheres are left out). Deterministic.
PhotonWorkload cornell_photon_workload(std::size_t n_photons, int width, int height,
                                       std::uint64_t seed = 1);

}  // namespace bench
