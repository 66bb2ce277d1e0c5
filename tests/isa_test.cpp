// Instruction sets (accel/isa.h): names, what this build targets against what the CPU has, and the
// SIMD width our kernels run at. scripts/test-isas builds the project again for every lower
// width the CPU can run and runs the structure and render tests there; these tests say which
// width a build has, so that its log shows each width was covered.

#include "accel/isa.h"
#include "accel/simd.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <cstdio>
#include <string>
#include <vector>

namespace {

TEST(Isa, NamesRoundTripAndLevelsAreOrdered) {
  int lanes = 0;
  for (accel::Isa isa : accel::kIsas) {
    EXPECT_EQ(accel::isa_from_name(accel::isa_name(isa)), isa);
    EXPECT_GE(accel::isa_lanes(isa), lanes);
    lanes = accel::isa_lanes(isa);
  }
  EXPECT_FALSE(accel::isa_from_name("avx9").has_value());
  EXPECT_EQ(accel::isa_list(accel::isa_bit(accel::Isa::Sse2) | accel::isa_bit(accel::Isa::Avx2)), "sse2, avx2");
}

TEST(Isa, TheCpuHasEveryLevelBelowItsHighest) {
  const accel::IsaSet cpu = accel::cpu_isas();
  EXPECT_TRUE(cpu & accel::isa_bit(accel::Isa::Sse2));
  bool gap = false;
  for (accel::Isa isa : accel::kIsas) {
    if (!(cpu & accel::isa_bit(isa))) gap = true;
    else EXPECT_FALSE(gap) << accel::isa_name(isa) << " without a level below it";
  }
  EXPECT_TRUE(cpu & accel::isa_bit(accel::build_isa())) << "built for " << accel::isa_name(accel::build_isa());
}

// A native build must use the widest level the CPU has: a build that silently fell back to a
// narrower one would leave that width untested on this machine.
TEST(Isa, ANativeBuildTargetsTheCpusHighestLevel) {
  const std::string configured = ACCELBENCH_ISA_NAME;
  std::printf("this build: ACCELBENCH_ISA=%s, level %s, %d float lanes per packet; the CPU has %s\n",
              configured.c_str(), accel::isa_name(accel::build_isa()), int(accel::simd::FloatPacket::size),
              accel::isa_list(accel::cpu_isas()).c_str());
  if (configured != "native") GTEST_SKIP() << "built for " << configured;
  const std::vector<accel::Isa> levels = accel::isas_in(accel::cpu_isas());
  EXPECT_EQ(accel::build_isa(), levels.back());
}

TEST(Isa, SimdKernelsRunAtTheBuildLevelsWidth) {
  EXPECT_EQ(int(accel::simd::FloatPacket::size), accel::isa_lanes(accel::build_isa()));
  EXPECT_EQ(int(accel::simd::FloatLeaf::size), std::min(8, accel::isa_lanes(accel::build_isa())));
  const std::string configured = ACCELBENCH_ISA_NAME;
  if (configured != "native") {
    EXPECT_EQ(accel::isa_name(accel::build_isa()), configured);
  }
}

// The node and box tests take max_or_second / min_or_second for the select they replace: equal
// bit for bit on NaN (a 0 * inf slab distance), signed zeros and infinities.
TEST(Simd, MaxOrSecondIsTheSelectItReplaces) {
  using B = accel::simd::FloatPacket;
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const float values[] = {nan, -inf, -1.5f, -0.0f, 0.0f, 1e-40f, 2.0f, inf};
  for (float x : values)
    for (float y : values) {
      const B a(x), b(y);
      const B want_max = xsimd::select(a > b, a, b), want_min = xsimd::select(a < b, a, b);
      const B got_max = accel::simd::max_or_second(a, b), got_min = accel::simd::min_or_second(a, b);
      EXPECT_EQ(std::bit_cast<std::uint32_t>(got_max.get(0)), std::bit_cast<std::uint32_t>(want_max.get(0)))
          << x << " " << y;
      EXPECT_EQ(std::bit_cast<std::uint32_t>(got_min.get(0)), std::bit_cast<std::uint32_t>(want_min.get(0)))
          << x << " " << y;
    }
}

}  // namespace
