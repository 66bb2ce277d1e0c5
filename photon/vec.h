#pragma once
// The photon code's vector and colour types, named once: glm::vec3, as tracer::Vec3 and
// tracer::Color are (the packed photon fields stay free of the tracer's headers).

#include <glm/vec3.hpp>

namespace photon {

using Vec3 = glm::vec3;   ///< World-space vector, as tracer::Vec3.
using Color = glm::vec3;  ///< Linear RGB, as tracer::Color.

}  // namespace photon
