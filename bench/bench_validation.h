#pragma once
// How the tracing benchmarks (bench_trace, trace_counts) check a structure's answers against
// naive's (or a reference checked against naive's) before they time or count it.

#include "accel/geometry.h"
#include "tracer/intersector.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace bench {

/// A structure whose own primitive routine answers (StructureInfo::exact false, embree_points,
/// embree_triangles) is validated within this tolerance: another primitive, or t more than
/// kToleranceT relative from naive's, for at most this share of the rays (or any-hit answers),
/// and every hit point within kToleranceT of the size of its coordinates (max(|org|, t |dir|)) of
/// naive's surface, measured along naive's normal there: a short secondary ray's t carries an ulp
/// of its origin, a large part of a t near 0, and a grazing ray's t is ill-conditioned (its error
/// divided by the cosine), which moves the point along the surface, not off it.
inline constexpr double kToleranceShare = 0.001;
inline constexpr double kToleranceT = 1e-5;
/// Its whole render is validated by the share of pixels more than 1% off naive's
/// (tracer::kPeerPixelsOffShare).

/// False for a structure that answers with its own primitive routine (StructureInfo::exact).
bool is_exact(const std::string& name);

/// The outcome of validating a structure's answers against naive's.
struct Validation {
  std::string why;             ///< Why it fails; "" when it passes.
  std::size_t self_hits = 0;   ///< A peer's hits within the rounding of the ray's origin (at_origin).
};

/// A peer's hit within the rounding of the ray's own origin: t |dir| at most kToleranceT of
/// |org|. Embree's default triangle routine reports such hits on the triangle a secondary ray
/// leaves (ogre: 120 of 110,953 shadow rays, at t near 1e-11), where the offset our watertight
/// routine's error bound gives the origin is enough for ours. Counted apart (counter
/// peer_self_hits), not as another answer: they are the peer routine's acne, not a lost primitive.
bool at_origin(const accel::Ray& ray, float t);

/// Whether `got` (the hits of `rays`) passes the check against naive's `want`: bit for bit (same
/// primitive, bit-equal t) for an exact structure, else within the tolerance, where naive's point
/// on a neighbouring primitive (t within 1e-5: a ray through a shared edge, coincident faces)
/// agrees.
Validation hit_mismatch(const tracer::Geometry& g, const std::vector<accel::Ray>& rays,
                        const std::vector<tracer::Hit>& got, const std::vector<tracer::Hit>& want, bool exact);

/// The same for any-hit answers; `closest_t(ray)` is the structure's closest hit, asked only of
/// the rays it answers otherwise than naive, to tell a peer's hits at the origin apart.
template <class ClosestT>
Validation blocked_mismatch(const std::vector<accel::Ray>& rays, const std::vector<std::uint8_t>& got,
                            const std::vector<std::uint8_t>& want, bool exact, ClosestT&& closest_t) {
  Validation v;
  std::size_t bad = 0;
  for (std::size_t i = 0; i < want.size(); ++i) {
    if (got[i] == want[i]) continue;
    if (!exact && got[i] && at_origin(rays[i], closest_t(rays[i])))
      ++v.self_hits;
    else
      ++bad;
  }
  const bool fails = exact ? bad > 0 : double(bad) > kToleranceShare * double(want.size());
  if (fails)
    v.why = std::to_string(bad) + " of " + std::to_string(want.size()) + " rays differ from naive" +
            (exact ? "" : " (tolerance 0.1%)");
  return v;
}

}  // namespace bench
