#pragma once
// How far a peer routine's hit point (Embree's spheres or triangles) is from naive's on the same
// ray, in units of the size of the point's coordinates, as the peer tests bound it.

#include "accel/geometry.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace peer_point {

/// |t - t_want| |dir| / max(|org|, t_want |dir|). Relative to t alone it would be ill-posed: a
/// short secondary ray's t carries an ulp of its origin, a large part of a t near 0.
inline double offset(const accel::Ray& ray, float t, float t_want) {
  const double len = double(glm::length(ray.dir));
  return std::abs(double(t) - double(t_want)) * len / std::max(double(glm::length(ray.org)), double(t_want) * len);
}

}  // namespace peer_point
