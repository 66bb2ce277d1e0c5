#pragma once
// The two ray/triangle routines of tracer/triangle.h (watertight and Moller-Trumbore) on a batch
// of triangles against one ray, for the structures' SIMD triangle leaves (triangle_soa.h). Every
// lane performs exactly the scalar routine's float operations in the same order, and the build
// forbids FMA contraction (-ffp-contract=off), so lane i gives the scalar t bit for bit: a
// structure with SIMD leaves reports naive's hits. tests/triangle_test.cpp holds them to that.

#include "geometry.h"
#include "simd.h"

#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <cstdint>

namespace accel {

/// A batch of triangles, one per lane: vertex v's coordinate on axis a in p[v][a].
template <class Batch>
struct TriangleLanes {
  Batch p[3][3];
};

/// What tracer::watertight_distance derives from the ray alone: the axis kz of the largest
/// direction component (x and y the next ones, cyclically) and the shear (sx, sy, sz).
struct WatertightRay {
  int kx = 0, ky = 1, kz = 2;
  float sx = 0.0f, sy = 0.0f, sz = 0.0f;
  bool valid = false;  ///< False when dir[kz] is 0 or not finite: the ray hits nothing.

  WatertightRay() = default;
  explicit WatertightRay(const Ray& ray) {
    // tracer::watertight_distance's choice of axes, without a branch: an incoherent ray's
    // largest component is a coin toss, and written as nested conditionals, or read through
    // glm's operator[] (a switch), it became branches the predictor missed (docs/meshes.md).
    // The same three comparisons give the same axes for every input, NaN included.
    const float* d = glm::value_ptr(ray.dir);
    const float ax = std::abs(d[0]), ay = std::abs(d[1]), az = std::abs(d[2]);
    const int x_over_y = ax > ay, x_over_z = ax > az, y_over_z = ay > az;
    kz = 2 - 2 * (x_over_y & x_over_z) - ((x_over_y ^ 1) & y_over_z);
    // The next axes cyclically, kz + 1 and kz + 2 mod 3, read from two-bit tables (0b001001:
    // 1, 2, 0; 0b010010: 2, 0, 1): written as comparisons, the compiler branched on them again.
    kx = (0b001001 >> (2 * kz)) & 3;
    ky = (0b010010 >> (2 * kz)) & 3;
    const float dz = d[kz];
    valid = dz != 0.0f && std::isfinite(dz);
    if (!valid) return;
    sx = -d[kx] / dz;
    sy = -d[ky] / dz;
    sz = 1.0f / dz;
  }
};

/// watertight_lanes on triangles whose coordinates are already on the ray's permuted axes:
/// tri.p[v][0], [1] and [2] hold vertex v's coordinates on axes w.kx, w.ky and w.kz. A
/// structure loads its rows in that order (triangle_soa.h), so no lane is moved at run time.
template <class Batch>
[[gnu::always_inline]] inline Batch watertight_lanes_permuted(const TriangleLanes<Batch>& tri, const Ray& ray,
                                                              const WatertightRay& w, std::uint32_t live = ~0u) {
  const Batch inf(kInfinity);
  if (!w.valid) return inf;
  const float* org = glm::value_ptr(ray.org);  // indexed, not through glm's operator[] (a switch)
  const Batch ox(org[w.kx]), oy(org[w.ky]), oz(org[w.kz]);
  // The vertices relative to the origin, on the permuted axes.
  const Batch a_x = tri.p[0][0] - ox, a_y = tri.p[0][1] - oy, a_z = tri.p[0][2] - oz;
  const Batch b_x = tri.p[1][0] - ox, b_y = tri.p[1][1] - oy, b_z = tri.p[1][2] - oz;
  const Batch c_x = tri.p[2][0] - ox, c_y = tri.p[2][1] - oy, c_z = tri.p[2][2] - oz;
  const Batch sx(w.sx), sy(w.sy), sz(w.sz);
  const Batch ax = a_x + sx * a_z, ay = a_y + sy * a_z;
  const Batch bx = b_x + sx * b_z, by = b_y + sy * b_z;
  const Batch cx = c_x + sx * c_z, cy = c_y + sy * c_z;
  Batch e0 = bx * cy - by * cx;
  Batch e1 = cx * ay - cy * ax;
  Batch e2 = ax * by - ay * bx;
  const Batch zero(0.0f);
  const std::uint32_t on_edge = simd::mask_bits<Batch>((e0 == zero) | (e1 == zero) | (e2 == zero)) & live;
  if (on_edge) {
    // The lanes with an edge function of exactly 0 take all three again in double, as the
    // scalar routine does (a product of floats is exact there).
    constexpr std::size_t n = Batch::size;
    alignas(64) float vx[3][n], vy[3][n], ev[3][n];
    ax.store_aligned(vx[0]), bx.store_aligned(vx[1]), cx.store_aligned(vx[2]);
    ay.store_aligned(vy[0]), by.store_aligned(vy[1]), cy.store_aligned(vy[2]);
    e0.store_aligned(ev[0]), e1.store_aligned(ev[1]), e2.store_aligned(ev[2]);
    for (std::uint32_t bits = on_edge; bits; bits &= bits - 1u) {
      const int i = simd::first_lane(bits);
      const double dax = vx[0][i], day = vy[0][i], dbx = vx[1][i], dby = vy[1][i], dcx = vx[2][i], dcy = vy[2][i];
      ev[0][i] = float(dbx * dcy - dby * dcx);
      ev[1][i] = float(dcx * day - dcy * dax);
      ev[2][i] = float(dax * dby - day * dbx);
    }
    e0 = Batch::load_aligned(ev[0]), e1 = Batch::load_aligned(ev[1]), e2 = Batch::load_aligned(ev[2]);
  }
  const auto mixed_signs = ((e0 < zero) | (e1 < zero) | (e2 < zero)) & ((e0 > zero) | (e1 > zero) | (e2 > zero));
  // Most rays pass beside every triangle of a leaf: then the distances are not needed.
  if ((~simd::mask_bits<Batch>(mixed_signs) & live) == 0) return inf;
  const Batch det = e0 + e1 + e2;
  const Batch az = sz * a_z, bz = sz * b_z, cz = sz * c_z;
  const Batch t_scaled = e0 * az + e1 * bz + e2 * cz;
  const Batch inv_det = Batch(1.0f) / det;
  const Batch t = t_scaled * inv_det;
  // The scalar routine's bound on the error of t (see tracer/triangle.h for its terms).
  const Batch max_z = xsimd::max(xsimd::max(xsimd::abs(az), xsimd::abs(bz)), xsimd::abs(cz));
  const Batch max_z_world = xsimd::max(xsimd::max(xsimd::abs(a_z), xsimd::abs(b_z)), xsimd::abs(c_z));
  const Batch max_x = xsimd::max(xsimd::max(xsimd::abs(ax), xsimd::abs(bx)), xsimd::abs(cx));
  const Batch max_y = xsimd::max(xsimd::max(xsimd::abs(ay), xsimd::abs(by)), xsimd::abs(cy));
  const Batch delta_z = Batch(gamma_bound(3)) * max_z;
  const Batch delta_x = Batch(gamma_bound(5)) * (max_x + max_z_world);
  const Batch delta_y = Batch(gamma_bound(5)) * (max_y + max_z_world);
  const Batch delta_e =
      Batch(2.0f) * (Batch(gamma_bound(2)) * max_x * max_y + delta_y * max_x + delta_x * max_y);
  const Batch max_e = xsimd::max(xsimd::max(xsimd::abs(e0), xsimd::abs(e1)), xsimd::abs(e2));
  const Batch delta_t =
      Batch(3.0f) * (Batch(gamma_bound(3)) * max_e * max_z + delta_e * max_z + delta_z * max_e) * xsimd::abs(inv_det);
  // !(det == 0 or det not finite) and t > tmin and t > delta_t, NaN failing each comparison.
  const auto keep = ~mixed_signs & (det != zero) & (xsimd::abs(det) < inf) & (t > Batch(ray.tmin)) & (t > delta_t);
  return xsimd::select(keep, t, inf);
}

/// tracer::watertight_distance<float> lane by lane: t of each triangle (> ray.tmin and above the
/// bound on its own rounding error), or +inf. Only the lanes of `live` (bit i: lane i) hold
/// triangles; the others may hold anything and come back as whatever they compute.
template <class Batch>
[[gnu::always_inline]] inline Batch watertight_lanes(const TriangleLanes<Batch>& tri, const Ray& ray,
                                                     const WatertightRay& w, std::uint32_t live = ~0u) {
  TriangleLanes<Batch> permuted;
  for (int v = 0; v < 3; ++v) {
    permuted.p[v][0] = tri.p[v][w.kx];
    permuted.p[v][1] = tri.p[v][w.ky];
    permuted.p[v][2] = tri.p[v][w.kz];
  }
  return watertight_lanes_permuted(permuted, ray, w, live);
}

/// tracer::moller_distance<float> lane by lane: t of each triangle (> ray.tmin), or +inf. glm's
/// cross(x, y) is (x.y y.z - y.y x.z, x.z y.x - y.z x.x, x.x y.y - y.x x.y) and its dot(u, v)
/// (u.x v.x + u.y v.y) + u.z v.z; those are the orders written here.
template <class Batch>
[[gnu::always_inline]] inline Batch moller_lanes(const TriangleLanes<Batch>& tri, const Ray& ray) {
  const Batch inf(kInfinity), zero(0.0f), one(1.0f);
  const Batch dx(ray.dir.x), dy(ray.dir.y), dz(ray.dir.z);
  const Batch e1x = tri.p[1][0] - tri.p[0][0], e1y = tri.p[1][1] - tri.p[0][1], e1z = tri.p[1][2] - tri.p[0][2];
  const Batch e2x = tri.p[2][0] - tri.p[0][0], e2y = tri.p[2][1] - tri.p[0][1], e2z = tri.p[2][2] - tri.p[0][2];
  const Batch pvx = dy * e2z - e2y * dz, pvy = dz * e2x - e2z * dx, pvz = dx * e2y - e2x * dy;
  const Batch det = (e1x * pvx + e1y * pvy) + e1z * pvz;
  const Batch inv_det = one / det;
  const Batch tvx = Batch(ray.org.x) - tri.p[0][0], tvy = Batch(ray.org.y) - tri.p[0][1],
              tvz = Batch(ray.org.z) - tri.p[0][2];
  const Batch u = ((tvx * pvx + tvy * pvy) + tvz * pvz) * inv_det;
  const auto u_in = (det != zero) & (xsimd::abs(det) < inf) & !(u < zero) & !(u > one);
  if (xsimd::none(u_in)) return inf;  // most rays pass beside every triangle of a leaf
  const Batch qvx = tvy * e1z - e1y * tvz, qvy = tvz * e1x - e1z * tvx, qvz = tvx * e1y - e1x * tvy;
  const Batch v = ((dx * qvx + dy * qvy) + dz * qvz) * inv_det;
  const Batch t = ((e2x * qvx + e2y * qvy) + e2z * qvz) * inv_det;
  // The scalar's early exits, as one mask: each comparison is false for NaN there as here.
  const auto keep = u_in & !(v < zero) & !(u + v > one) & (t > Batch(ray.tmin));
  return xsimd::select(keep, t, inf);
}

}  // namespace accel
