// Google Benchmark: k-nearest-neighbour gathers over photon maps, one thread.
//
//   Knn/N:<photons>/<structure>/k:<k>/r:<inf|0.1>   queries per second (items_per_second) for
//       the balanced heap (the paper's tree), the median and sliding-midpoint bucket trees,
//       brute force and nanoflann 1.4.3, on the same photons and queries; cull off (nanoflann
//       has no hemisphere test), cache_distances on. r:inf is unbounded on both sides (nanoflann
//       with its own KNNResultSet); r:0.1 is bounded at 0.1 units on both sides (nanoflann with
//       bench/nanoflann_knn.h's result set whose worst distance starts at r^2).
//   Opt/N:<photons>/<tree>/cull:<0|1>/cache:<0|1>/k:<k>   the paper's optimisations 2 and 3
//       switched on and off, per tree (optimisation 1, balancing: balanced vs the others).
//   Build/N:<photons>/<structure>/threads:<1|all>   tree construction, wall-clock time (the
//       balanced tree also on every core).
//
// Photons and queries: the Cornell box's (scenes_gen "cornell", a box 2 units wide) global photon
// map, traced by the photon integrator's global pass, and the diffuse first hits of its 64 x 64
// camera rays (bench/photon_workload.h). Before anything is timed, each structure's answer
// for every timed query is compared with an independent brute-force reference: the same photons
// (original indices) and bit-equal squared distances, or for nanoflann, which orders equal
// distances as it meets them, the same distances and the same photon wherever a distance is not
// tied. A mismatch skips that benchmark with an error and makes the binary exit non-zero.
// Brute force itself is timed on every 16th (N = 10^5) or 64th (N = 10^6) query. Query rates are
// CPU time of the benchmark thread; builds are wall-clock time.
//
//   build/bin/bench_photon --benchmark_filter='Knn/N:1000000/.*/k:50/'
//   build/bin/bench_photon --benchmark_repetitions=3 --benchmark_enable_random_interleaving=true
//       --benchmark_out=results/bench_photon.json --benchmark_out_format=json

#include "nanoflann_knn.h"
#include "photon_workload.h"
#include "validated_main.h"

#include "photon/photon_map.h"
#include "tracer/parallel.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <bit>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace {

using bench::PhotonQuery;
using bench::PhotonWorkload;
using bench_photon::NanoflannPhotons;
using photon::GatherParams;
using photon::Neighbors;
using photon::Photon;
using photon::PhotonMap;
using photon::PhotonTreeKind;
using photon::PhotonTreeParams;

constexpr int kGrid = 64;
constexpr int kMaxK = 500;
constexpr int kKs[] = {1, 8, 50, 200, 500};
constexpr std::size_t kSizes[] = {10'000, 100'000, 1'000'000};
constexpr float kBoundedRadius = 0.1f;
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr std::uint64_t kSeed = 2024;

int g_validation_failures = 0;

struct Found {
  float d2;
  std::uint32_t id;
};
bool before(const Found& a, const Found& b) { return a.d2 < b.d2 || (a.d2 == b.d2 && a.id < b.id); }

/// The kMaxK nearest photons of every query, sorted by (d2, id), computed independently of
/// photon/ (a scan with a growing radius, then a sort), on all cores.
struct Reference {
  std::vector<Found> found;         // kMaxK slots per query
  std::vector<std::uint32_t> count;  // valid entries per query

  Reference(const PhotonWorkload& set, bool cull) {
    const std::size_t nq = set.queries.size();
    found.resize(nq * kMaxK);
    count.resize(nq);
    const int threads = tracer::resolve_threads(0);
    std::vector<std::vector<Found>> nears(threads);  // one scratch list per worker
    tracer::parallel_items(threads, int(nq), [&](int worker, int item) {
      const std::size_t q = std::size_t(item);
      std::vector<Found>& near = nears[worker];
      const PhotonQuery& qp = set.queries[q];
      for (float r2 = 1e-4f;; r2 *= 4.0f) {
        near.clear();
        for (std::uint32_t i = 0; i < set.photons.size(); ++i) {
          const photon::Vec3& p = set.photons[i].position;
          const float dx = qp.position.x - p.x, dy = qp.position.y - p.y,
                      dz = qp.position.z - p.z;
          const float d2 = dx * dx + dy * dy + dz * dz;
          if (d2 < r2 && (!cull || set.photons[i].arrives_from_side_of(qp.normal)))
            near.push_back({d2, i});
        }
        if (near.size() >= kMaxK || r2 > 64.0f) break;  // the box's diagonal is 3.5: 64 is all
      }
      std::sort(near.begin(), near.end(), before);
      const std::size_t n = std::min<std::size_t>(near.size(), kMaxK);
      std::copy(near.begin(), near.begin() + n, found.begin() + q * kMaxK);
      count[q] = std::uint32_t(n);
    });
  }

  /// The expected answer for query q, k photons, radius r.
  std::vector<Found> expected(std::size_t q, int k, float r) const {
    const float r2 = r * r;
    std::vector<Found> out;
    for (std::uint32_t i = 0; i < count[q] && int(out.size()) < k; ++i) {
      const Found& f = found[q * kMaxK + i];
      if (!(f.d2 < r2)) break;
      out.push_back(f);
    }
    return out;
  }
};

struct Dataset {
  PhotonWorkload set;
  std::unique_ptr<Reference> reference[2];  // [cull]
  std::map<std::string, std::unique_ptr<PhotonMap>> maps;
  std::unique_ptr<NanoflannPhotons> nano;

  const Reference& ref(bool cull) {
    if (!reference[cull]) reference[cull] = std::make_unique<Reference>(set, cull);
    return *reference[cull];
  }
  const PhotonMap& map(PhotonTreeKind kind) {
    const std::string key(photon::name_of(kind));
    auto& m = maps[key];
    if (!m) m = std::make_unique<PhotonMap>(set.photons, PhotonTreeParams{kind});
    return *m;
  }
  const NanoflannPhotons& nanoflann() {
    if (!nano) nano = std::make_unique<NanoflannPhotons>(set.photons);
    return *nano;
  }
};

Dataset& dataset(std::size_t n) {
  static std::map<std::size_t, std::unique_ptr<Dataset>> all;
  auto& d = all[n];
  if (!d) {
    d = std::make_unique<Dataset>();
    d->set = bench::cornell_photon_workload(n, kGrid, kGrid, kSeed);
  }
  return *d;
}

std::size_t stride_for(PhotonTreeKind kind, std::size_t n) {
  if (kind != PhotonTreeKind::BruteForce) return 1;
  return n >= 1'000'000 ? 64 : (n >= 100'000 ? 16 : 1);
}

std::string describe(const std::vector<Found>& v) {
  std::string s = std::to_string(v.size()) + " photons:";
  for (std::size_t i = 0; i < v.size() && i < 6; ++i)
    s += " (" + std::to_string(v[i].id) + ", " + std::to_string(v[i].d2) + ")";
  return s;
}

/// Fails the benchmark (and the binary) with `what`.
void fail(benchmark::State& st, const std::string& what) {
  std::fprintf(stderr, "bench_photon: VALIDATION FAILED: %s\n", what.c_str());
  ++g_validation_failures;
  st.SkipWithError(("validation failed: " + what).c_str());
}

/// Checks a photon map's answers for the timed queries; returns an empty string when all match.
std::string validate_map(Dataset& d, const PhotonMap& map, const GatherParams& gp, std::size_t stride) {
  const Reference& ref = d.ref(gp.cull);
  Neighbors nb;
  for (std::size_t q = 0; q < d.set.queries.size(); q += stride) {
    const PhotonQuery& qp = d.set.queries[q];
    map.gather(qp.position, qp.normal, gp, nb);
    std::vector<Found> got;
    for (const photon::Neighbor& n : nb.items()) got.push_back({n.d2, map.original_index(n.slot)});
    std::sort(got.begin(), got.end(), before);
    const std::vector<Found> want = ref.expected(q, gp.k, gp.max_radius);
    bool same = got.size() == want.size();
    for (std::size_t i = 0; same && i < got.size(); ++i)
      same = got[i].id == want[i].id &&
             std::bit_cast<std::uint32_t>(got[i].d2) == std::bit_cast<std::uint32_t>(want[i].d2);
    if (!same)
      return "query " + std::to_string(q) + ": want " + describe(want) + ", got " + describe(got);
  }
  return "";
}

void bm_gather(benchmark::State& st, std::size_t n, PhotonTreeKind kind, GatherParams gp) {
  Dataset& d = dataset(n);
  const PhotonMap& map = d.map(kind);
  const std::size_t stride = stride_for(kind, n);
  if (const std::string err = validate_map(d, map, gp, stride); !err.empty()) return fail(st, err);
  const auto& queries = d.set.queries;
  std::visit(
      [&](const auto& tree) {
        Neighbors nb;
        for (auto _ : st) {
          for (std::size_t q = 0; q < queries.size(); q += stride) {
            PhotonMap::gather_in<false>(tree, queries[q].position, queries[q].normal, gp, nb, nullptr);
            benchmark::DoNotOptimize(nb.items().data());
          }
          benchmark::ClobberMemory();
        }
      },
      map.tree());
  const std::size_t per_iteration = (queries.size() + stride - 1) / stride;
  st.SetItemsProcessed(std::int64_t(st.iterations() * per_iteration));
  // An untimed counting pass: work per query.
  photon::GatherCounters c;
  Neighbors nb;
  for (std::size_t q = 0; q < queries.size(); q += stride)
    map.gather<true>(queries[q].position, queries[q].normal, gp, nb, &c);
  st.counters["photons_tested_per_query"] = double(c.photons_tested) / double(c.lookups);
  st.counters["nodes_per_query"] = double(c.nodes_visited) / double(c.lookups);
  st.counters["heap_inserts_per_query"] = double(c.heap_inserts) / double(c.lookups);
  st.counters["found_per_query"] = double(c.photons_found) / double(c.lookups);
  st.counters["photons"] = double(n);
  st.counters["queries"] = double(per_iteration);
}

void bm_nanoflann(benchmark::State& st, std::size_t n, int k, float radius) {
  Dataset& d = dataset(n);
  const NanoflannPhotons& nano = d.nanoflann();
  const Reference& ref = d.ref(false);
  const auto& queries = d.set.queries;
  std::vector<std::uint32_t> ids;
  std::vector<float> d2;
  const auto search = [&](const photon::Vec3& q) {
    return std::isinf(radius) ? nano.knn_unbounded(q, std::size_t(k), ids, d2)
                              : nano.knn(q, std::size_t(k), radius, ids, d2);
  };
  for (std::size_t q = 0; q < queries.size(); ++q) {
    const std::size_t found = search(queries[q].position);
    const std::vector<Found> want = ref.expected(q, k, radius);
    bool same = found == want.size();
    for (std::size_t i = 0; same && i < found; ++i) {
      same = std::bit_cast<std::uint32_t>(d2[i]) == std::bit_cast<std::uint32_t>(want[i].d2);
      const bool tied = (i > 0 && want[i - 1].d2 == want[i].d2) ||
                        (i + 1 < want.size() && want[i + 1].d2 == want[i].d2) || i + 1 == found;
      if (same && !tied) same = ids[i] == want[i].id;
    }
    if (!same) return fail(st, "nanoflann, query " + std::to_string(q) + ": want " + describe(want));
  }
  for (auto _ : st) {
    for (const PhotonQuery& qp : queries) {
      benchmark::DoNotOptimize(search(qp.position));
      benchmark::DoNotOptimize(d2.data());
    }
    benchmark::ClobberMemory();
  }
  st.SetItemsProcessed(std::int64_t(st.iterations() * queries.size()));
  st.counters["photons"] = double(n);
  st.counters["queries"] = double(queries.size());
}

template <class Build>
void bm_build(benchmark::State& st, std::size_t n, Build build) {
  Dataset& d = dataset(n);
  for (auto _ : st) build(d.set.photons);
  st.SetItemsProcessed(std::int64_t(st.iterations() * n));
  st.counters["photons"] = double(n);
}

std::string radius_name(float r) { return std::isinf(r) ? "inf" : "0.1"; }

constexpr PhotonTreeKind kTrees[] = {PhotonTreeKind::Balanced, PhotonTreeKind::MedianBuckets,
                                     PhotonTreeKind::SlidingMidpoint};

void register_all() {
  for (const std::size_t n : kSizes) {
    const std::string N = "N:" + std::to_string(n);
    for (const float r : {kInf, kBoundedRadius}) {
      for (const int k : kKs) {
        const std::string tail = "/k:" + std::to_string(k) + "/r:" + radius_name(r);
        for (const PhotonTreeKind kind :
             {PhotonTreeKind::Balanced, PhotonTreeKind::MedianBuckets,
              PhotonTreeKind::SlidingMidpoint, PhotonTreeKind::BruteForce}) {
          benchmark::RegisterBenchmark(
              ("Knn/" + N + "/" + std::string(photon::name_of(kind)) + tail).c_str(),
              [=](benchmark::State& st) { bm_gather(st, n, kind, GatherParams{k, r, false, true}); })
              ->Unit(benchmark::kMicrosecond);
        }
        benchmark::RegisterBenchmark(("Knn/" + N + "/nanoflann" + tail).c_str(),
                                     [=](benchmark::State& st) { bm_nanoflann(st, n, k, r); })
            ->Unit(benchmark::kMicrosecond);
      }
    }
  }
  for (const std::size_t n : {std::size_t(100'000), std::size_t(1'000'000)}) {
    const std::string N = "N:" + std::to_string(n);
    for (const int k : {50, 200}) {
      for (const PhotonTreeKind kind : kTrees) {
        for (const bool cull : {false, true}) {
          for (const bool cache : {false, true}) {
            benchmark::RegisterBenchmark(
                ("Opt/" + N + "/" + std::string(photon::name_of(kind)) + "/cull:" +
                 std::to_string(cull) + "/cache:" + std::to_string(cache) + "/k:" + std::to_string(k))
                    .c_str(),
                [=](benchmark::State& st) {
                  bm_gather(st, n, kind, GatherParams{k, kInf, cull, cache});
                })
                ->Unit(benchmark::kMicrosecond);
          }
        }
      }
    }
  }
  for (const std::size_t n : kSizes) {
    const std::string N = "N:" + std::to_string(n);
    for (const PhotonTreeKind kind : kTrees) {
      // One thread for every tree; the balanced tree also on every core (build_threads 0).
      for (const int threads : {1, 0}) {
        if (threads == 0 && kind != PhotonTreeKind::Balanced) continue;
        const std::string name = "Build/" + N + "/" + std::string(photon::name_of(kind)) +
                                 "/threads:" + (threads ? "1" : "all");
        benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& st) {
          bm_build(st, n, [&](const std::vector<Photon>& p) {
            PhotonTreeParams params{kind};
            params.build_threads = threads;
            const PhotonMap m(p, params);
            benchmark::DoNotOptimize(m.size());
          });
        })->Unit(benchmark::kMillisecond)->UseRealTime();
      }
    }
    benchmark::RegisterBenchmark(("Build/" + N + "/nanoflann/threads:1").c_str(), [=](benchmark::State& st) {
      bm_build(st, n, [&](const std::vector<Photon>& p) {
        const NanoflannPhotons nano(p);
        benchmark::DoNotOptimize(&nano);
      });
    })->Unit(benchmark::kMillisecond)->UseRealTime();
  }
}

}  // namespace

int main(int argc, char** argv) {
  return bench::run_validated_benchmarks(
      argc, argv, register_all, g_validation_failures,
      "bench_photon: %d benchmark(s) failed validation against brute force\n", /*bad_arguments_status=*/2);
}
