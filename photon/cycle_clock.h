#pragma once
// A cheap clock for timing many short calls inside a render (kNN gathers, direct light): the
// time-stamp counter where there is one, steady_clock nanoseconds elsewhere. Ticks become
// milliseconds through a rate measured against steady_clock over the whole loop.

#include <chrono>
#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

namespace photon {

/// Ticks of the cycle clock: monotonic on one machine, rate constant (an invariant TSC).
inline std::uint64_t cycle_ticks() {
#if defined(__x86_64__) || defined(__i386__)
  return __rdtsc();
#else
  return std::uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(
                           std::chrono::steady_clock::now().time_since_epoch())
                           .count());
#endif
}

/// Measures the tick rate between construction and ms_per_tick().
class TickRate {
 public:
  TickRate() : t0_(std::chrono::steady_clock::now()), c0_(cycle_ticks()) {}
  /// Milliseconds per tick over the time since construction (0 before any tick passed).
  double ms_per_tick() const {
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0_).count();
    const std::uint64_t ticks = cycle_ticks() - c0_;
    return ticks > 0 ? ms / double(ticks) : 0.0;
  }

 private:
  std::chrono::steady_clock::time_point t0_;
  std::uint64_t c0_;
};

}  // namespace photon
