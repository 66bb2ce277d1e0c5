#include "isa.h"

#include <cpuid.h>

namespace accel {

const char* isa_name(Isa isa) {
  switch (isa) {
    case Isa::Sse2: return "sse2";
    case Isa::Sse42: return "sse4.2";
    case Isa::Avx: return "avx";
    case Isa::Avx2: return "avx2";
    case Isa::Avx512: return "avx512";
  }
  return "";
}

std::optional<Isa> isa_from_name(std::string_view name) {
  for (Isa isa : kIsas)
    if (name == isa_name(isa)) return isa;
  return std::nullopt;
}

const char* isa_features(Isa isa) {
  switch (isa) {
    case Isa::Sse2: return "SSE2";
    case Isa::Sse42: return "SSE4.2 and POPCNT";
    case Isa::Avx: return "AVX and F16C";
    case Isa::Avx2: return "AVX2, FMA, BMI1, BMI2 and LZCNT";
    case Isa::Avx512: return "AVX-512 F, CD, DQ, BW and VL";
  }
  return "";
}

int isa_lanes(Isa isa) {
  switch (isa) {
    case Isa::Sse2:
    case Isa::Sse42: return 4;
    case Isa::Avx:
    case Isa::Avx2: return 8;
    case Isa::Avx512: return 16;
  }
  return 4;
}

namespace {

/// Bit `bit` of register ECX of CPUID leaf `leaf`; false when the CPU has no such leaf. F16C and
/// LZCNT are read here rather than through __builtin_cpu_supports, whose names for them clang 14
/// rejects: with them no clang build compiled this file (scripts/fuzz builds with clang).
bool cpuid_ecx_bit(unsigned leaf, unsigned bit) {
  unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
  if (!__get_cpuid(leaf, &eax, &ebx, &ecx, &edx)) return false;
  return (ecx >> bit) & 1u;
}

bool cpu_has_f16c() { return cpuid_ecx_bit(1, 29); }            // CPUID.1:ECX.F16C[bit 29]
bool cpu_has_lzcnt() { return cpuid_ecx_bit(0x80000001u, 5); }  // CPUID.80000001H:ECX.LZCNT[bit 5]

}  // namespace

IsaSet cpu_isas() {
  __builtin_cpu_init();
  IsaSet set = isa_bit(Isa::Sse2);  // every x86-64 CPU
  const bool sse42 = __builtin_cpu_supports("sse4.2") && __builtin_cpu_supports("popcnt");
  const bool avx = sse42 && __builtin_cpu_supports("avx") && cpu_has_f16c();
  const bool avx2 = avx && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
                    __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2") && cpu_has_lzcnt();
  const bool avx512 = avx2 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
                      __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
                      __builtin_cpu_supports("avx512vl");
  if (sse42) set |= isa_bit(Isa::Sse42);
  if (avx) set |= isa_bit(Isa::Avx);
  if (avx2) set |= isa_bit(Isa::Avx2);
  if (avx512) set |= isa_bit(Isa::Avx512);
  return set;
}

std::vector<Isa> isas_in(IsaSet set) {
  std::vector<Isa> out;
  for (Isa isa : kIsas)
    if (set & isa_bit(isa)) out.push_back(isa);
  return out;
}

std::string isa_list(IsaSet set) {
  std::string s;
  for (Isa isa : isas_in(set)) {
    if (!s.empty()) s += ", ";
    s += isa_name(isa);
  }
  return s;
}

}  // namespace accel
