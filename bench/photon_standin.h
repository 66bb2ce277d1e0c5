#pragma once
// A stand-in for the Cornell box's global photon map and its camera-ray diffuse hits, for
// bench_photon until engineer render's photon tracer provides the real ones.
//
// The box is [0,1]^3 (floor y = 0, ceiling y = 1, back wall z = 0, open at z = 1) with two
// spheres of radius 0.18 on the floor; a point light below the ceiling centre emits uniformly.
// Photons are traced through diffuse bounces only (walls and spheres are all Lambertian, albedo
// 0.7 white, red and green side walls, Russian roulette with survival 0.7), and every diffuse hit
// is stored, the first included. Queries are the first hits of a grid of camera rays from
// (0.5, 0.5, 2.2) looking at the box, with the surface normal facing the camera. This gives the
// spatial structure that matters for a kNN tree (photons on 2-D surfaces meeting at corners,
// density falling with distance to the light, curved surfaces) but no caustics.

#include "photon/photon.h"

#include <cstdint>
#include <vector>

namespace bench_photon {

/// A gather position and its shading normal.
struct QueryPoint {
  photon::Vec3 position;  ///< World units.
  photon::Vec3 normal;    ///< Unit surface normal on the camera's side.
};

struct PhotonBenchSet {
  std::vector<photon::Photon> photons;  ///< Stored photons, in tracing order.
  std::vector<QueryPoint> queries;      ///< Camera-ray hits, row by row.
};

/// `n` photons and `grid` x `grid` queries, the same for the same arguments on every machine.
PhotonBenchSet cornell_standin(std::size_t n, int grid, std::uint64_t seed);

}  // namespace bench_photon
