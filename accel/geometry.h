#pragma once
// Rays and axis-aligned boxes: the only geometry the acceleration structures know.

#include <glm/vec3.hpp>
#include <glm/geometric.hpp>
#include <glm/common.hpp>

#include <cstdint>
#include <limits>

namespace accel {

using Vec3 = glm::vec3;

inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

/// A ray with its valid parametric interval [tmin, tmax]. Traversal may shorten tmax.
struct Ray {
  Vec3 org{0.0f};            ///< Origin, world units.
  float tmin = 0.0f;         ///< Nearest accepted hit distance, in units of |dir|.
  Vec3 dir{0.0f, 0.0f, 1.0f};  ///< Direction; need not be unit length.
  float tmax = kInfinity;    ///< Farthest accepted hit distance; shortened by closest-hit leaf tests.
};

/// Bound on the relative rounding error of n floating-point operations (pbrt's gamma(n)).
inline constexpr float gamma_bound(int n) {
  constexpr float eps = std::numeric_limits<float>::epsilon() * 0.5f;
  return (n * eps) / (1.0f - n * eps);
}

/// Axis-aligned bounding box. The default box is empty (lo = +inf, hi = -inf).
struct Aabb {
  Vec3 lo{kInfinity};   ///< Minimum corner.
  Vec3 hi{-kInfinity};  ///< Maximum corner.

  static Aabb of_point(const Vec3& p) { return {p, p}; }

  void grow(const Vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void grow(const Aabb& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  bool is_empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  Vec3 extent() const { return hi - lo; }
  Vec3 center() const { return 0.5f * (lo + hi); }
  /// Half the surface area; the SAH only ever needs ratios, so the factor 2 is dropped.
  float half_area() const {
    if (is_empty()) return 0.0f;
    const Vec3 e = extent();
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }
  /// Index (0, 1, 2) of the longest axis.
  int longest_axis() const {
    const Vec3 e = extent();
    return (e.x >= e.y && e.x >= e.z) ? 0 : (e.y >= e.z ? 1 : 2);
  }
  bool overlaps(const Aabb& b) const {
    return lo.x <= b.hi.x && b.lo.x <= hi.x && lo.y <= b.hi.y && b.lo.y <= hi.y &&
           lo.z <= b.hi.z && b.lo.z <= hi.z;
  }
  bool contains(const Aabb& b) const {
    return lo.x <= b.lo.x && lo.y <= b.lo.y && lo.z <= b.lo.z && b.hi.x <= hi.x &&
           b.hi.y <= hi.y && b.hi.z <= hi.z;
  }
};

static_assert(sizeof(Aabb) == 24, "Aabb is two packed float3");

}  // namespace accel
