// The host's own two-thread ceiling: how much faster two threads finish a load that has nothing
// to share, on this machine, now. The two-thread render target (two threads >= 1.9x one) is a
// ratio of wall times, and a shared or virtual host may not give two threads twice one thread's
// speed even for work with no memory traffic at all (other tenants, clocks that drop when both
// cores run). scripts/bench_embree runs this beside each pair of renders, so the render's scaling
// can be read against what the host allowed in the same minute.
//
// The load is the render's shape: `--items` items (the render's 3,072 tiles of 1024x768) handed
// out by the tracer's own pool (tracer::parallel_items, started before the clock as the render
// starts it), each item a dependent chain of `--iterations` steps. With `--working-set-kb 0` a
// step is a multiply-add in registers (no memory at all); with K > 0 it is a load from a table of
// K KiB that both threads share, read-only, in a random cycle (a pointer chase: every load waits
// for the one before, as a traversal's node loads do). On a host whose cores share caches or
// memory with other tenants, the second ceiling lies below the first. Pairs alternate their order
// (one thread first, then two first) as the render pairs do.
//
//   build/bin/thread_ceiling [--pairs 5] [--items 3072] [--iterations 37000] [--working-set-kb 0]
//                            [--json FILE]

#include "tracer/parallel.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace {

struct Options {
  int pairs = 5;
  int items = 3072;
  int iterations = 37000;
  int working_set_kb = 0;
  std::string json_path;
};

/// One item without memory: a multiply-add chain whose every step waits for the one before, so
/// the core's time is the chain's latency and nothing else (no loads, no stores but the result).
double chain(int iterations, double seed) {
  double a = seed;
  for (int i = 0; i < iterations; ++i) a = a * 0.999999999 + 1e-9;
  return a;
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
    sink[std::size_t(item)] = table.empty() ? chain(o.iterations, double(item))
                                            : chase(o.iterations, table, std::uint32_t(item) % table.size());
  });
  const auto stop = std::chrono::steady_clock::now();
  return std::chrono::duration<double, std::milli>(stop - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"The host's two-thread ceiling: one and two threads on a load with no memory traffic"};
  app.add_option("--pairs", o.pairs, "pairs of one- and two-thread runs")->check(CLI::Range(1, 1000));
  app.add_option("--items", o.items, "items per run (the render's tiles)")->check(CLI::Range(2, 1 << 20));
  app.add_option("--iterations", o.iterations, "multiply-adds per item")->check(CLI::Range(1, 100000000));
  app.add_option("--working-set-kb", o.working_set_kb, "KiB of the shared table each step loads from; 0: none")
      ->check(CLI::Range(0, 1 << 20));
  app.add_option("--json", o.json_path, "write the pairs here as JSON");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "thread_ceiling: %s\n", e.what());
    return 2;
  }

  const std::vector<std::uint32_t> table = o.working_set_kb > 0 ? random_cycle(o.working_set_kb)
                                                                : std::vector<std::uint32_t>{};
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
