#pragma once
// The one ray-sphere routine: the scalar version every structure reaches through the tracer's
// leaf function, and the same operations lane by lane on a batch of spheres (the SIMD leaf
// tests). Both give the same t to the bit: every lane performs exactly the scalar routine's
// operations, in the same order, and the build forbids FMA contraction (-ffp-contract=off).

#include "geometry.h"
#include "simd.h"
#include "sphere_root.h"

#include <cmath>
#include <utility>

namespace accel {

/// A sphere as the structures see it: enough to test a ray against it, nothing about shading.
struct SphereShape {
  Vec3 center{0.0f};  ///< Centre, world units.
  float radius = 1.0f;  ///< Radius, world units (> 0).
};

/// sphere_root in float: what every structure's sphere leaf computes.
inline float intersect_sphere(const Vec3& center, float radius, const Ray& ray) {
  return sphere_root<float>(center, radius, ray);
}

/// sphere_root's operations on a batch of lanes, each lane one (sphere, ray) pair: ray origin
/// o, direction d with a = dot(d, d), interval start tmin, sphere centre c and radius r. Lane i
/// equals intersect_sphere(c_i, r_i, ray_i) bit for bit. glm::dot(u, v) is
/// (u.x v.x + u.y v.y) + u.z v.z, and that is the order written here.
// GCC 12 warns that the AVX-512 sqrt intrinsic's own undefined pass-through register "may be
// used uninitialized" (GCC bug 105593, fixed in GCC 13); it is not.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
template <class Batch>
[[gnu::always_inline]] inline Batch sphere_root_lanes(const Batch& ox, const Batch& oy, const Batch& oz, const Batch& dx,
                               const Batch& dy, const Batch& dz, const Batch& a, const Batch& tmin,
                               const Batch& cx, const Batch& cy, const Batch& cz, const Batch& r) {
  const Batch fx = ox - cx, fy = oy - cy, fz = oz - cz;
  const Batch b = (fx * dx + fy * dy) + fz * dz;
  const Batch k = b / a;
  const Batch lx = fx - k * dx, ly = fy - k * dy, lz = fz - k * dz;
  const Batch r2 = r * r;
  const Batch disc = a * (r2 - ((lx * lx + ly * ly) + lz * lz));
  const auto hit = disc >= Batch(0.0f);  // false for NaN, as !(disc >= 0) is true in the scalar
  const Batch inf(kInfinity);
  if (xsimd::none(hit)) return inf;  // every lane misses: skip the roots
  const Batch c = ((fx * fx + fy * fy) + fz * fz) - r2;
  const Batch q = -b - xsimd::copysign(xsimd::sqrt(disc), b);
  const auto degenerate = q == Batch(0.0f);
  Batch t0 = xsimd::select(degenerate, Batch(0.0f), c / q);
  Batch t1 = xsimd::select(degenerate, Batch(0.0f), q / a);
  const auto swap = t0 > t1;
  const Batch lo = xsimd::select(swap, t1, t0), hi = xsimd::select(swap, t0, t1);
  const Batch t = xsimd::select(lo > tmin, lo, xsimd::select(hi > tmin, hi, inf));
  return xsimd::select(hit, t, inf);
}
#pragma GCC diagnostic pop

/// intersect_sphere on Batch::size spheres at once (centres cx, cy, cz, radii r), for one ray.
/// Lane i equals intersect_sphere(center_i, r_i, ray) bit for bit.
template <class Batch>
[[gnu::always_inline]] inline Batch intersect_spheres(const Batch& cx, const Batch& cy, const Batch& cz, const Batch& r,
                               const Ray& ray) {
  const float a = glm::dot(ray.dir, ray.dir);
  return sphere_root_lanes(Batch(ray.org.x), Batch(ray.org.y), Batch(ray.org.z), Batch(ray.dir.x),
                           Batch(ray.dir.y), Batch(ray.dir.z), Batch(a), Batch(ray.tmin), cx, cy, cz, r);
}

}  // namespace accel
