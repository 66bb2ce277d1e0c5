#pragma once
// The x86-64 SIMD levels the project tells apart: the one this build was compiled for, the ones
// the CPU it runs on has, and their names (Embree's spellings, used by its `isa` knob).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace accel {

/// An x86-64 SIMD level; each includes the ones before it.
enum class Isa : std::uint8_t {
  Sse2,    ///< x86-64 baseline: 4 float lanes.
  Sse42,   ///< SSE4.1, SSE4.2 and POPCNT: 4 lanes.
  Avx,     ///< AVX and F16C: 8 lanes.
  Avx2,    ///< AVX2, FMA, BMI1/2 and LZCNT (x86-64-v3): 8 lanes.
  Avx512,  ///< AVX-512 F, CD, DQ, BW and VL (x86-64-v4): 16 lanes.
};

/// Every level, lowest first.
inline constexpr Isa kIsas[] = {Isa::Sse2, Isa::Sse42, Isa::Avx, Isa::Avx2, Isa::Avx512};

/// Embree's name of a level: "sse2", "sse4.2", "avx", "avx2", "avx512".
const char* isa_name(Isa isa);
/// The level called `name` (isa_name spelling), or nullopt.
std::optional<Isa> isa_from_name(std::string_view name);
/// The CPU features a level needs, in words, for error messages ("AVX-512 F, CD, DQ, BW and VL").
const char* isa_features(Isa isa);
/// Float lanes of one SIMD register at that level: 4, 8 or 16.
int isa_lanes(Isa isa);

/// A set of levels, bit (1 << level).
using IsaSet = std::uint32_t;
inline constexpr IsaSet isa_bit(Isa isa) { return IsaSet(1) << unsigned(isa); }

/// The highest level this build's compiler flags target (ACCELBENCH_ISA); every SIMD kernel of
/// ours runs at this width.
constexpr Isa build_isa() {
#if defined(__AVX512F__) && defined(__AVX512CD__) && defined(__AVX512DQ__) && defined(__AVX512BW__) && \
    defined(__AVX512VL__)
  return Isa::Avx512;
#elif defined(__AVX2__) && defined(__FMA__) && defined(__BMI2__) && defined(__LZCNT__)
  return Isa::Avx2;
#elif defined(__AVX__)
  return Isa::Avx;
#elif defined(__SSE4_2__)
  return Isa::Sse42;
#else
  return Isa::Sse2;
#endif
}

/// The levels the CPU running this process has.
IsaSet cpu_isas();
/// The levels of `set`, lowest first.
std::vector<Isa> isas_in(IsaSet set);
/// The names of the levels of `set`, lowest first, separated by ", ".
std::string isa_list(IsaSet set);

}  // namespace accel
