// The host's own two-thread ceiling: how much faster two threads finish a load that has nothing
// to share, on this machine, now. The two-thread render target (two threads >= 1.9x one) is a
// ratio of wall times, and a shared or virtual host may not give two threads twice one thread's
// speed even for work with no memory traffic at all (other tenants, clocks that drop when both
// cores run). scripts/bench_embree runs this beside each pair of renders, so the render's scaling
// can be read against what the host allowed in the same minute.
//
// The load has the render's shape: `--items` items (the render's 3,072 tiles of 1024x768) handed
// out by the tracer's own pool (tracer::parallel_items, started before the clock as the render
// starts it), each item `--iterations` steps of one of three kinds (`--load`):
// - `registers`: one multiply-add chain, each step waiting for the one before: the core's
//   latency, no memory, little power;
// - `vector`: 128 independent multiply-add lanes (the compiler's vectors at the build's ISA): the
//   core's full throughput, the power a wide load draws (a host may lower both cores' clocks when
//   both run such a load);
// - `table`: a load from a table of `--working-set-kb` KiB shared by both threads, read-only, in
//   a random cycle (a pointer chase: each load waits for the one before, as a traversal's node
//   loads do); on a host whose cores share caches with other tenants this ceiling falls.
// Pairs alternate their order (one thread first, then two first) as the render pairs do.
//
//   build/bin/thread_ceiling [--load registers|vector|table] [--pairs 5] [--items 3072]
//                            [--iterations 37000] [--working-set-kb 320] [--json FILE]

#include "tracer/parallel.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <map>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace {

struct Options {
  int pairs = 5;
  int items = 3072;
  enum class Load { Registers, Vector, Table } load = Load::Registers;
  int iterations = 37000;
  int working_set_kb = 320;
  std::string json_path;
};

/// The loads by their flag names.
const std::map<std::string, Options::Load> kLoads = {
    {"registers", Options::Load::Registers}, {"vector", Options::Load::Vector}, {"table", Options::Load::Table}};

/// The flag name of `load`.
std::string load_name(Options::Load load) {
  for (const auto& [name, value] : kLoads)
    if (value == load) return name;
  return "?";
}

/// One item without memory: a multiply-add chain whose every step waits for the one before, so
/// the core's time is the chain's latency and nothing else (no loads, no stores but the result).
double chain(int iterations, double seed) {
  double a = seed;
  for (int i = 0; i < iterations; ++i) a = a * 0.999999999 + 1e-9;
  return a;
}

/// One item at the core's vector throughput: 128 independent lanes (8 AVX-512 or 16 AVX2
/// registers of chains, enough to keep two 4-cycle multiply-add pipes busy), `iterations` steps
/// each: about as long as a registers item (both 180-200 ms a run on the Zen 5 VM of December 2026).
float lanes(int iterations, float seed) {
  constexpr int kLanes = 128;
  float a[kLanes];
  for (int j = 0; j < kLanes; ++j) a[j] = seed + float(j);
  for (int i = 0; i < iterations; ++i)
    for (int j = 0; j < kLanes; ++j) a[j] = a[j] * 0.9999999f + 1e-7f;
  float sum = 0.0f;
  for (int j = 0; j < kLanes; ++j) sum += a[j];
  return sum;
}

/// One item through memory: `iterations` dependent loads along `next`, a single random cycle.
double chase(int iterations, const std::vector<std::uint32_t>& next, std::uint32_t start) {
  std::uint32_t at = start;
  for (int i = 0; i < iterations; ++i) at = next[at];
  return double(at);
}

/// A random cycle through every slot of a table of `kb` KiB (fixed seed: the same every run).
std::vector<std::uint32_t> random_cycle(int kb) {
  const std::size_t n = std::size_t(kb) * 1024 / sizeof(std::uint32_t);
  std::vector<std::uint32_t> order(n), next(n);
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), std::mt19937(12345));
  for (std::size_t i = 0; i < n; ++i) next[order[i]] = order[(i + 1) % n];
  return next;
}

/// Wall milliseconds for every item on `threads` threads.
double run(const Options& o, int threads, const std::vector<std::uint32_t>& table, std::vector<double>& sink) {
  tracer::prepare_threads(threads);
  const auto start = std::chrono::steady_clock::now();
  tracer::parallel_items(threads, o.items, [&](int, int item) {
    double& out = sink[std::size_t(item)];
    switch (o.load) {
      case Options::Load::Registers: out = chain(o.iterations, double(item)); break;
      case Options::Load::Vector: out = double(lanes(o.iterations, float(item))); break;
      case Options::Load::Table: out = chase(o.iterations, table, std::uint32_t(item) % table.size()); break;
    }
  });
  const auto stop = std::chrono::steady_clock::now();
  return std::chrono::duration<double, std::milli>(stop - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"The host's two-thread ceiling: one and two threads on a load with nothing to share"};
  app.add_option("--pairs", o.pairs, "pairs of one- and two-thread runs")->check(CLI::Range(1, 1000));
  app.add_option("--items", o.items, "items per run (the render's tiles)")->check(CLI::Range(2, 1 << 20));
  app.add_option("--iterations", o.iterations, "steps per item")->check(CLI::Range(1, 100000000));
  app.add_option("--load", o.load, "registers, vector or table")->transform(CLI::CheckedTransformer(kLoads));
  app.add_option("--working-set-kb", o.working_set_kb, "KiB of the shared table of --load table")
      ->check(CLI::Range(1, 1 << 20));
  app.add_option("--json", o.json_path, "write the pairs here as JSON");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "thread_ceiling: %s\n", e.what());
    return 2;
  }

  const std::vector<std::uint32_t> table =
      o.load == Options::Load::Table ? random_cycle(o.working_set_kb) : std::vector<std::uint32_t>{};
  std::vector<double> sink(std::size_t(o.items), 0.0);
  nlohmann::json pairs = nlohmann::json::array();
  std::vector<double> ratios;
  for (int p = 0; p < o.pairs; ++p) {
    double one = 0.0, two = 0.0;
    if (p % 2 == 0) {
      one = run(o, 1, table, sink);
      two = run(o, 2, table, sink);
    } else {
      two = run(o, 2, table, sink);
      one = run(o, 1, table, sink);
    }
    ratios.push_back(one / two);
    pairs.push_back({{"one_ms", one}, {"two_ms", two}, {"ratio", one / two}});
    std::printf("pair %d: one thread %.2f ms, two threads %.2f ms, ratio %.3f\n", p + 1, one, two, one / two);
  }
  std::sort(ratios.begin(), ratios.end());
  const std::size_t n = ratios.size();
  const double median = n % 2 ? ratios[n / 2] : 0.5 * (ratios[n / 2 - 1] + ratios[n / 2]);
  double checksum = 0.0;
  for (double s : sink) checksum += s;
  std::printf("median ratio %.3f over %zu pairs (checksum %.6g)\n", median, n, checksum);

  if (!o.json_path.empty()) {
    const nlohmann::json out = {{"items", o.items}, {"iterations", o.iterations},
                                {"load", load_name(o.load)},
                                {"working_set_kb", o.working_set_kb}, {"pairs", pairs},
                                {"median_ratio", median}};
    std::ofstream f(o.json_path);
    f << out.dump(2) << "\n";
    if (!f) {
      std::fprintf(stderr, "thread_ceiling: --json: cannot write %s\n", o.json_path.c_str());
      return 1;
    }
  }
  return 0;
}
