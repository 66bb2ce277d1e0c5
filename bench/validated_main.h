#pragma once
// The main() of a Google Benchmark binary whose benchmarks check their answers before timing:
// runs what the command line selects, then exits non-zero when any check failed.

#include "accel/isa.h"

#include <benchmark/benchmark.h>

#include <cstdio>

namespace bench {

/// Registers (register_all), runs and reports the benchmarks; `failures` counts the checks that
/// failed meanwhile. Returns the process's exit status: 1 when any check failed (saying so with
/// `complaint`, e.g. "bench_trace: %d structure(s) failed validation against naive\n"),
/// `bad_arguments_status` on an argument Google Benchmark does not know, else 0.
inline int run_validated_benchmarks(int argc, char** argv, void (*register_all)(), const int& failures,
                                    const char* complaint, int bad_arguments_status = 1) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return bad_arguments_status;
  register_all();
  // The instruction set every figure names: the level this build targets, and the CPU's levels.
  benchmark::AddCustomContext("isa", accel::isa_name(accel::build_isa()));
  benchmark::AddCustomContext("cpu_isas", accel::isa_list(accel::cpu_isas()));
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  if (failures > 0) {
    std::fprintf(stderr, complaint, failures);
    return 1;
  }
  return 0;
}

}  // namespace bench
