#include "bench_validation.h"

#include "accel/accel.h"
#include "tracer/surface.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace bench {

using accel::Ray;
using accel::Vec3;
using tracer::Hit;

bool is_exact(const std::string& name) {
  const accel::StructureInfo* info = accel::find_structure(name);
  return !info || info->exact;
}

bool at_origin(const Ray& ray, float t) {
  return t < accel::kInfinity &&
         double(t) * double(glm::length(ray.dir)) <= kToleranceT * double(glm::length(ray.org));
}

Validation hit_mismatch(const tracer::Geometry& g, const std::vector<Ray>& rays, const std::vector<Hit>& got,
                        const std::vector<Hit>& want, bool exact) {
  Validation v;
  std::size_t bad = 0, other = 0;
  double max_point = 0.0;
  for (std::size_t i = 0; i < want.size(); ++i) {
    bad += got[i].prim != want[i].prim ||
           std::bit_cast<std::uint32_t>(got[i].t) != std::bit_cast<std::uint32_t>(want[i].t);
    const double dt = std::abs(double(got[i].t) - double(want[i].t));
    if (got[i].prim != want[i].prim) {
      if (at_origin(rays[i], got[i].t))
        ++v.self_hits;
      else if (!(got[i].found() && want[i].found() && !got[i].is_plane() && !want[i].is_plane() &&
                 dt <= kToleranceT * double(want[i].t)))
        ++other;
    } else if (want[i].found() && want[i].t > 0.0f) {
      other += dt > kToleranceT * double(want[i].t);
      if (exact) continue;
      const double len = double(glm::length(rays[i].dir));
      const Vec3 n = tracer::surface_point(g, rays[i], want[i], tracer::TriangleTest::Watertight).n_geo;
      const double cos = std::abs(double(glm::dot(rays[i].dir, n))) / (len * double(glm::length(n)));
      const double off = dt * len * cos / std::max(double(glm::length(rays[i].org)), double(want[i].t) * len);
      max_point = std::max(max_point, off);
    }
  }
  const std::string of = " of " + std::to_string(want.size()) + " rays";
  if (exact) {
    if (bad) v.why = std::to_string(bad) + of + " differ from naive";
  } else if (double(other) > kToleranceShare * double(want.size())) {
    v.why = std::to_string(other) + of + " hit another primitive than naive or t more than 1e-5 off (tolerance 0.1%)";
  } else if (max_point > kToleranceT) {
    v.why = "a hit point lies " + std::to_string(max_point) + " of its coordinates off naive's surface (tolerance 1e-5)";
  }
  return v;
}

}  // namespace bench
