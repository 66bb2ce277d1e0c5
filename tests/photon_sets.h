#pragma once
// Seeded photon sets for the photon-map tests: the distributions where kd-trees go wrong.

#include "photon/photon.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace photon_sets {

using photon::Photon;
using photon::Vec3;

enum class SetKind {
  Random,      ///< Uniform in [-1, 1]^3.
  Clustered,   ///< Tight Gaussian clusters over a sparse uniform background.
  Coplanar,    ///< All on the plane z = 0.25 (one axis of zero extent).
  Lattice,     ///< Points of a 1/8 lattice: exact coordinates, many equal distances (ties).
  Duplicates,  ///< A few positions, each repeated many times (zero-size cells, r = 0).
};

inline const char* name_of(SetKind k) {
  switch (k) {
    case SetKind::Random: return "random";
    case SetKind::Clustered: return "clustered";
    case SetKind::Coplanar: return "coplanar";
    case SetKind::Lattice: return "lattice";
    case SetKind::Duplicates: return "duplicates";
  }
  return "?";
}

inline constexpr SetKind kAllKinds[] = {SetKind::Random, SetKind::Clustered, SetKind::Coplanar,
                                        SetKind::Lattice, SetKind::Duplicates};

inline Vec3 random_direction(std::mt19937& rng) {
  std::normal_distribution<float> g(0.0f, 1.0f);
  for (;;) {
    const Vec3 v(g(rng), g(rng), g(rng));
    const float l = glm::length(v);
    if (l > 1e-3f) return v / l;
  }
}

/// n photons of kind `kind` with random directions and powers in [0.5, 1.5) W per channel.
inline std::vector<Photon> make_set(SetKind kind, std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), pw(0.5f, 1.5f);
  std::uniform_int_distribution<int> lattice(-8, 8);
  std::vector<Vec3> centres;
  for (int c = 0; c < 5; ++c) centres.emplace_back(u(rng), u(rng), u(rng));
  std::normal_distribution<float> tight(0.0f, 0.01f);
  std::vector<Photon> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 p;
    switch (kind) {
      case SetKind::Random:
        p = Vec3(u(rng), u(rng), u(rng));
        break;
      case SetKind::Clustered:
        if (i % 10 == 0) {
          p = Vec3(u(rng), u(rng), u(rng));
        } else {
          const Vec3& c = centres[i % centres.size()];
          p = c + Vec3(tight(rng), tight(rng), tight(rng));
        }
        break;
      case SetKind::Coplanar:
        p = Vec3(u(rng), u(rng), 0.25f);
        break;
      case SetKind::Lattice:
        p = Vec3(float(lattice(rng)), float(lattice(rng)), float(lattice(rng))) * 0.125f;
        break;
      case SetKind::Duplicates:
        p = centres[std::uniform_int_distribution<std::size_t>(0, 2)(rng)];
        break;
    }
    out.push_back(Photon::make(p, Vec3(pw(rng), pw(rng), pw(rng)), random_direction(rng)));
  }
  return out;
}

/// Query points for a set: random points around it, the photons' own positions, lattice points
/// and points far outside.
inline std::vector<Vec3> make_queries(const std::vector<Photon>& photons, std::size_t n,
                                      std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.2f, 1.2f);
  std::uniform_int_distribution<int> lattice(-9, 9);
  std::vector<Vec3> q;
  for (std::size_t i = 0; i < n; ++i) {
    switch (i % 4) {
      case 0:
        q.emplace_back(u(rng), u(rng), u(rng));
        break;
      case 1:
        if (!photons.empty()) {
          q.push_back(photons[std::uniform_int_distribution<std::size_t>(0, photons.size() - 1)(rng)].position);
          break;
        }
        [[fallthrough]];
      case 2:
        q.push_back(Vec3(float(lattice(rng)), float(lattice(rng)), float(lattice(rng))) * 0.125f);
        break;
      default:
        q.push_back(Vec3(u(rng), u(rng), u(rng)) * 20.0f);
        break;
    }
  }
  return q;
}

}  // namespace photon_sets
