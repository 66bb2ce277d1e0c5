#pragma once
// A right-handed orthonormal frame (t, b, n) around a unit vector n, branchless and continuous
// except at n.z = 0's sign flip (Duff, Burgess, Christensen, Hery, Kensler, Liani and Villemin,
// "Building an Orthonormal Basis, Revisited", JCGT 2017). The photon tracer's cosine directions,
// the light's emission cones and the sphereflake's child directions all build their frames here.

#include <glm/vec3.hpp>

#include <cmath>

namespace tracer {

/// t and b such that (t, b, n) is right-handed and orthonormal; n must be unit length.
inline void orthonormal_basis(const glm::vec3& n, glm::vec3& t, glm::vec3& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

}  // namespace tracer
