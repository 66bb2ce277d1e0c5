// The photon map's k-nearest-neighbour gather (photon/knn.h, photon/photon_map.h) is exact:
// every tree variant, with every switch on and off, returns the same photons and the same
// squared distances as an independent brute-force search, ties broken by original index; and
// nanoflann agrees on the distances.

#include "photon/photon_map.h"

#include "bench/nanoflann_knn.h"
#include "photon_sets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace {

using photon::GatherParams;
using photon::Neighbors;
using photon::Photon;
using photon::PhotonMap;
using photon::PhotonTreeKind;
using photon::PhotonTreeParams;
using photon::Vec3;
using photon_sets::SetKind;

constexpr float kInf = std::numeric_limits<float>::infinity();

struct Found {
  float d2;
  std::uint32_t id;
  bool operator==(const Found& o) const {
    return std::bit_cast<std::uint32_t>(d2) == std::bit_cast<std::uint32_t>(o.d2) && id == o.id;
  }
};

/// Every photon (culled by `normal` when cull), sorted by (d2, id): the reference, written
/// independently of photon/neighbor_heap.h.
std::vector<Found> all_sorted(const std::vector<Photon>& photons, const Vec3& q, const Vec3& normal,
                              bool cull) {
  std::vector<Found> all;
  for (std::uint32_t i = 0; i < photons.size(); ++i) {
    const Vec3& p = photons[i].position;
    const float dx = q.x - p.x, dy = q.y - p.y, dz = q.z - p.z;
    if (cull && !photons[i].arrives_from_side_of(normal)) continue;
    all.push_back({dx * dx + dy * dy + dz * dz, i});
  }
  std::sort(all.begin(), all.end(), [](const Found& a, const Found& b) {
    return a.d2 < b.d2 || (a.d2 == b.d2 && a.id < b.id);
  });
  return all;
}

/// The first k of `all` closer than max_radius.
std::vector<Found> expected(const std::vector<Found>& all, int k, float max_radius) {
  const float r2 = max_radius * max_radius;
  std::vector<Found> out;
  for (const Found& f : all) {
    if (int(out.size()) == k || !(f.d2 < r2)) break;
    out.push_back(f);
  }
  return out;
}

std::vector<Found> found_by(const PhotonMap& map, const Neighbors& nb) {
  std::vector<Found> out;
  for (const photon::Neighbor& n : nb.items()) out.push_back({n.d2, map.original_index(n.slot)});
  std::sort(out.begin(), out.end(), [](const Found& a, const Found& b) {
    return a.d2 < b.d2 || (a.d2 == b.d2 && a.id < b.id);
  });
  return out;
}

std::string describe(const std::vector<Found>& v) {
  std::ostringstream s;
  s << v.size() << " photons:";
  for (std::size_t i = 0; i < v.size() && i < 12; ++i) s << " (" << v[i].id << ", " << v[i].d2 << ")";
  return s.str();
}

struct Variant {
  PhotonTreeKind kind;
  int leaf_size;
};
constexpr Variant kVariants[] = {
    {PhotonTreeKind::BruteForce, 8},      {PhotonTreeKind::Balanced, 8},
    {PhotonTreeKind::SlidingMidpoint, 1}, {PhotonTreeKind::SlidingMidpoint, 3},
    {PhotonTreeKind::SlidingMidpoint, 8}, {PhotonTreeKind::SlidingMidpoint, 32},
    {PhotonTreeKind::MedianBuckets, 1},   {PhotonTreeKind::MedianBuckets, 8},
};

std::string variant_name(const Variant& v) {
  return std::string(photon::name_of(v.kind)) + "/leaf" + std::to_string(v.leaf_size);
}

/// Checks every variant and switch against the reference on one photon set; returns the number
/// of gathers checked.
std::size_t check_set(const std::vector<Photon>& photons, const std::vector<Vec3>& queries,
                      const std::string& label) {
  std::vector<PhotonMap> maps;
  for (const Variant& v : kVariants) maps.emplace_back(photons, PhotonTreeParams{v.kind, v.leaf_size});
  const int n = int(photons.size());
  const int ks[] = {1, 2, 7, 50, std::max(1, n), n + 5};
  const float radii[] = {0.05f, 0.3f, kInf};
  std::mt19937 rng(7);
  Neighbors nb;
  std::size_t checked = 0;
  for (std::size_t qi = 0; qi < queries.size(); ++qi) {
    const Vec3& q = queries[qi];
    const Vec3 normal = photon_sets::random_direction(rng);
    for (const bool cull : {false, true}) {
      const std::vector<Found> all = all_sorted(photons, q, normal, cull);
      for (const int k : ks) {
        for (const float r : radii) {
          const std::vector<Found> want = expected(all, k, r);
          std::vector<photon::Neighbor> raw_cached;
          for (std::size_t v = 0; v < maps.size(); ++v) {
            for (const bool cache : {true, false}) {
              const GatherParams params{k, r, cull, cache};
              maps[v].gather(q, normal, params, nb);
              const std::vector<Found> got = found_by(maps[v], nb);
              ++checked;
              if (got != want) {
                ADD_FAILURE() << label << " " << variant_name(kVariants[v]) << " query " << qi << " ("
                              << q.x << ", " << q.y << ", " << q.z << ") k=" << k << " r=" << r
                              << " cull=" << cull << " cache=" << cache << "\n  want "
                              << describe(want) << "\n  got  " << describe(got);
                return checked;
              }
              // cache_distances cannot change the answer, so it must not change a bit of it,
              // heap order included.
              const std::vector<photon::Neighbor> raw(nb.items().begin(), nb.items().end());
              if (cache) {
                raw_cached = raw;
              } else {
                bool same = raw.size() == raw_cached.size();
                for (std::size_t i = 0; same && i < raw.size(); ++i)
                  same = raw[i].slot == raw_cached[i].slot &&
                         std::bit_cast<std::uint32_t>(raw[i].d2) ==
                             std::bit_cast<std::uint32_t>(raw_cached[i].d2);
                if (!same) {
                  ADD_FAILURE() << label << " " << variant_name(kVariants[v]) << " query " << qi
                                << ": cache_distances off changed the heap";
                  return checked;
                }
              }
            }
          }
        }
      }
    }
  }
  return checked;
}

TEST(Knn, ExactAgainstBruteForceEverySetVariantAndSwitch) {
  std::size_t checked = 0;
  for (const SetKind kind : photon_sets::kAllKinds) {
    for (const std::size_t n : {0u, 1u, 2u, 3u, 7u, 8u, 9u, 100u, 1023u, 1024u, 1025u, 2500u}) {
      const auto photons = photon_sets::make_set(kind, n, std::uint32_t(n * 31 + 5));
      const auto queries = photon_sets::make_queries(photons, n > 1000 ? 24 : 40, std::uint32_t(n + 1));
      const std::string label = std::string(photon_sets::name_of(kind)) + " N=" + std::to_string(n);
      checked += check_set(photons, queries, label);
      if (HasFailure()) return;
    }
  }
  EXPECT_GT(checked, 100000u);
}

// Jensen's locate_photons stops at half = N/2 - 1 and never reaches the last photons; a gather
// for k = 1 at each photon's own position must find a photon at distance 0, for every N.
TEST(Knn, EveryPhotonIsReachableInEverySmallTree) {
  for (const Variant& v : kVariants) {
    for (std::size_t n = 1; n <= 70; ++n) {
      const auto photons = photon_sets::make_set(SetKind::Random, n, std::uint32_t(n));
      const PhotonMap map(photons, {v.kind, v.leaf_size});
      Neighbors nb;
      for (std::uint32_t i = 0; i < n; ++i) {
        map.gather(photons[i].position, Vec3(0.0f), {1, kInf, false, true}, nb);
        ASSERT_EQ(nb.size(), 1) << variant_name(v) << " N=" << n;
        EXPECT_EQ(map.original_index(nb.items()[0].slot), i) << variant_name(v) << " N=" << n;
        EXPECT_EQ(nb.items()[0].d2, 0.0f);
      }
    }
  }
}

TEST(Knn, EmptyMapAndFewerThanK) {
  Neighbors nb;
  const PhotonMap none;
  none.gather(Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), {}, nb);
  EXPECT_TRUE(nb.empty());
  EXPECT_FALSE(nb.full());
  for (const Variant& v : kVariants) {
    const PhotonMap empty(std::vector<Photon>{}, {v.kind, v.leaf_size});
    empty.gather(Vec3(0.0f), Vec3(0.0f), {5, kInf, false, true}, nb);
    EXPECT_TRUE(nb.empty()) << variant_name(v);
    const auto three = photon_sets::make_set(SetKind::Random, 3, 1);
    const PhotonMap map(three, {v.kind, v.leaf_size});
    map.gather(Vec3(0.0f), Vec3(0.0f), {5, kInf, false, true}, nb);
    EXPECT_EQ(nb.size(), 3) << variant_name(v);
    EXPECT_FALSE(nb.full());
    EXPECT_EQ(nb.k(), 5);
  }
}

TEST(Knn, NonFiniteQueryFindsNothing) {
  const auto photons = photon_sets::make_set(SetKind::Random, 100, 3);
  for (const Variant& v : kVariants) {
    const PhotonMap map(photons, {v.kind, v.leaf_size});
    Neighbors nb;
    for (const float bad : {std::nanf(""), kInf, -kInf}) {
      map.gather(Vec3(0.1f, bad, 0.2f), Vec3(0.0f), {5, kInf, false, true}, nb);
      EXPECT_TRUE(nb.empty()) << variant_name(v);
      EXPECT_EQ(nb.k(), 5);
    }
  }
}

TEST(Knn, ZeroNormalCullsNothing) {
  const auto photons = photon_sets::make_set(SetKind::Random, 500, 3);
  const PhotonMap map(photons, {PhotonTreeKind::Balanced, 8});
  Neighbors a, b;
  map.gather(Vec3(0.1f), Vec3(0.0f), {20, kInf, true, true}, a);
  map.gather(Vec3(0.1f), Vec3(0.0f), {20, kInf, false, true}, b);
  EXPECT_EQ(found_by(map, a), found_by(map, b));
}

TEST(Knn, CountersCountTheWork) {
  const auto photons = photon_sets::make_set(SetKind::Random, 5000, 4);
  for (const Variant& v : kVariants) {
    const PhotonMap map(photons, {v.kind, v.leaf_size});
    photon::GatherCounters c;
    Neighbors nb, plain;
    map.gather<true>(Vec3(0.2f), Vec3(0.0f, 0.0f, 1.0f), {50, 0.5f, true, true}, nb, &c);
    map.gather(Vec3(0.2f), Vec3(0.0f, 0.0f, 1.0f), {50, 0.5f, true, true}, plain);
    EXPECT_EQ(found_by(map, nb), found_by(map, plain)) << variant_name(v);
    EXPECT_EQ(c.lookups, 1u);
    EXPECT_EQ(c.photons_found, 50u);
    EXPECT_GE(c.heap_inserts, 50u);
    EXPECT_GE(c.photons_tested, c.heap_inserts + c.photons_culled);
    EXPECT_GT(c.photons_culled, 0u) << variant_name(v);
    if (v.kind == PhotonTreeKind::BruteForce) {
      EXPECT_EQ(c.photons_tested, 5000u);
    } else {
      EXPECT_LT(c.photons_tested, 2500u) << variant_name(v) << ": the tree prunes nothing";
    }
  }
}

TEST(Knn, BadKnobsNameTheKnob) {
  const auto photons = photon_sets::make_set(SetKind::Random, 10, 1);
  const PhotonMap map(photons, {});
  Neighbors nb;
  const auto message = [&](GatherParams p) -> std::string {
    try {
      map.gather(Vec3(0.0f), Vec3(0.0f), p, nb);
    } catch (const knobs::ConfigError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(message({0, 1.0f, true, true}), "gather: knob 'k' must be in [1, 1048576], got 0");
  EXPECT_EQ(message({-3, 1.0f, true, true}), "gather: knob 'k' must be in [1, 1048576], got -3");
  EXPECT_EQ(message({5, 0.0f, true, true}), "gather: knob 'max_radius' must be > 0.0 or \"inf\", got 0.0");
  EXPECT_EQ(message({5, -1.0f, true, true}), "gather: knob 'max_radius' must be > 0.0 or \"inf\", got -1.0");
  EXPECT_EQ(message({5, std::nanf(""), true, true}), "gather: knob 'max_radius' must be > 0.0 or \"inf\", got nan");
  EXPECT_EQ(message({5, kInf, true, true}), "no error");
}

TEST(Knn, ParamsJsonRoundTripAndRejects) {
  GatherParams p{12, 0.25f, false, false};
  const nlohmann::json j = p;
  GatherParams back = j.get<GatherParams>();
  EXPECT_EQ(back.k, 12);
  EXPECT_EQ(back.max_radius, 0.25f);
  EXPECT_FALSE(back.cull);
  EXPECT_FALSE(back.cache_distances);
  p.max_radius = kInf;
  EXPECT_TRUE(std::isinf(nlohmann::json(p).get<GatherParams>().max_radius));
  const auto error = [](const char* text) -> std::string {
    try {
      nlohmann::json::parse(text).get<GatherParams>();
    } catch (const knobs::ConfigError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(error(R"({"k": 0})"), "gather: knob 'k' must be in [1, 1048576], got 0");
  EXPECT_EQ(error(R"({"max_radius": -2})"),
            "gather: knob 'max_radius' must be > 0.0 or \"inf\", got -2");
  EXPECT_EQ(error(R"({"max_radius": "big"})"),
            "gather: knob 'max_radius' must be a number or \"inf\", got \"big\"");
  EXPECT_EQ(error(R"({"kk": 3})"), "gather: unknown knob 'kk' (its knobs: k, max_radius, cull, cache_distances)");
}

// nanoflann 1.4.3 as a second opinion: the same squared distances (bit for bit: both compute
// (q-p).x^2 + (q-p).y^2 + (q-p).z^2 left to right, without FMA contraction) for the same k and
// radius, and the same photons wherever a distance is not tied.
TEST(Knn, NanoflannAgrees) {
  std::size_t ids_compared = 0;
  for (const SetKind kind : {SetKind::Random, SetKind::Clustered, SetKind::Coplanar, SetKind::Lattice}) {
    const auto photons = photon_sets::make_set(kind, 20000, 11);
    const auto queries = photon_sets::make_queries(photons, 300, 12);
    const bench_photon::NanoflannPhotons nano(photons);
    const PhotonMap balanced(photons, {PhotonTreeKind::Balanced, 8});
    const PhotonMap bucket(photons, {PhotonTreeKind::SlidingMidpoint, 8});
    std::vector<std::uint32_t> ids;
    std::vector<float> d2;
    Neighbors nb;
    for (const int k : {1, 8, 50, 200}) {
      for (const float r : {0.1f, kInf}) {
        for (const Vec3& q : queries) {
          const std::size_t n = nano.knn(q, std::size_t(k), r, ids, d2);
          for (const PhotonMap* map : {&balanced, &bucket}) {
            map->gather(q, Vec3(0.0f), {k, r, false, true}, nb);
            const std::vector<Found> ours = found_by(*map, nb);
            ASSERT_EQ(ours.size(), n) << photon_sets::name_of(kind) << " k=" << k << " r=" << r;
            for (std::size_t i = 0; i < n; ++i) {
              ASSERT_EQ(ours[i].d2, d2[i]) << photon_sets::name_of(kind) << " k=" << k << " i=" << i;
              // Float distances do tie now and then, and nanoflann orders ties as it meets
              // them: compare the photon where its distance is unique in the list.
              const bool unique = (i == 0 || d2[i - 1] != d2[i]) && i + 1 < n && d2[i + 1] != d2[i];
              if (unique) {
                ASSERT_EQ(ours[i].id, ids[i]) << photon_sets::name_of(kind) << " k=" << k << " i=" << i;
                ++ids_compared;
              }
            }
          }
        }
      }
    }
  }
  EXPECT_GT(ids_compared, 500000u);
}

}  // namespace
