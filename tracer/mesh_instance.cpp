#include "mesh_instance.h"

#include <cmath>
#include <numbers>

namespace tracer {

glm::dmat3 MeshTransform::linear() const {
  const auto axis_rotation = [](int axis, double degrees) {
    const double a = degrees * std::numbers::pi / 180.0;
    const double c = std::cos(a), s = std::sin(a);
    glm::dmat3 m(1.0);  // column-major: m[column][row]
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;
    m[i][i] = c;
    m[i][j] = s;
    m[j][i] = -s;
    m[j][j] = c;
    return m;
  };
  glm::dmat3 s(1.0);
  s[0][0] = scale.x;
  s[1][1] = scale.y;
  s[2][2] = scale.z;
  return axis_rotation(2, rotate.z) * axis_rotation(1, rotate.y) * axis_rotation(0, rotate.x) * s;
}

accel::Vec3 MeshTransform::apply(const accel::Vec3& p) const {
  if (is_identity()) return p;
  return accel::Vec3(translate + linear() * glm::dvec3(p));
}

}  // namespace tracer
