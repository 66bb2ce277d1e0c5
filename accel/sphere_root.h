#pragma once
// The ray-sphere root, for any scalar type: the structures' sphere leaves (accel/sphere_hit.h, in
// float, scalar and SIMD) and the tracer's float and double paths (tracer/sphere.h) all compute
// exactly this.

#include <glm/glm.hpp>

#include <cmath>
#include <limits>
#include <utility>

namespace accel {

/// Nearest root t > tmin of |org + t dir - center| = radius, or +inf when there is none, in the
/// scalar type T of the ray (float here and in the structures; double in the tracer's reference).
///
/// The discriminant is computed as a (r^2 - |f - (f.d / a) d|^2), which keeps its precision when
/// the sphere is many radii away, where b^2 - ac cancels to noise; the roots use the stable form
/// q = -b - sign(b) sqrt(disc), t0 = c / q, t1 = q / a (Ray Tracing Gems, ch. 7).
template <class T, class V, class R>
T sphere_root(const V& center, T radius, const R& ray) {
  constexpr T inf = std::numeric_limits<T>::infinity();
  const V f = ray.org - center;
  const T a = glm::dot(ray.dir, ray.dir);
  const T b = glm::dot(f, ray.dir);  // half of the usual b
  const V l = f - (b / a) * ray.dir;
  const T r2 = radius * radius;
  const T disc = a * (r2 - glm::dot(l, l));
  if (!(disc >= T(0))) return inf;
  const T c = glm::dot(f, f) - r2;
  const T q = -b - std::copysign(std::sqrt(disc), b);
  T t0 = c / q;
  T t1 = q / a;
  if (q == T(0)) t0 = t1 = T(0);  // ray origin at the centre of a zero sphere; degenerate
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > ray.tmin) return t0;
  if (t1 > ray.tmin) return t1;
  return inf;
}

}  // namespace accel
