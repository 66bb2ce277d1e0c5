#pragma once
// The SIMD vocabulary of the structures, on xsimd (Debian's libxsimd-dev): fixed-width float
// batches picked from the instruction sets this build targets, and a lane mask as bits. Every
// SIMD kernel is written once against these names and compiles for AVX-512, AVX2 and plain
// SSE2 alike (ACCELBENCH_ISA).

#include <xsimd/xsimd.hpp>

#include <bit>
#include <cstdint>
#include <type_traits>

#if !defined(__x86_64__)
#error "accel/simd.h relies on x86's MAXPS and MINPS semantics (max_or_second)"
#endif

namespace accel::simd {

/// A batch of exactly N floats on the best instruction set this build has for that width, or
/// void when none has it (8 lanes need AVX).
template <int N>
using FloatN = xsimd::make_sized_batch_t<float, std::size_t(N)>;

/// 4 floats (SSE2 and up, so every x86-64 build).
using Float4 = FloatN<4>;
static_assert(!std::is_void_v<Float4>, "xsimd offers no 4-float batch for this target");

/// The widest of 8 and 4 lanes this build has: what leaf tests run on.
using FloatLeaf = std::conditional_t<std::is_void_v<FloatN<8>>, Float4, FloatN<8>>;

/// The batch a ray packet runs on, one ray per lane: 16 lanes where the target has AVX-512, else
/// the leaf batch (8 or 4).
using FloatPacket = std::conditional_t<std::is_void_v<FloatN<16>>, FloatLeaf, FloatN<16>>;

/// A batch of 16 floats in one AVX-512 register, which the helpers below handle by intrinsics.
template <class Batch>
inline constexpr bool kZmm =
#if XSIMD_WITH_AVX512F
    Batch::size == 16 && std::is_base_of_v<xsimd::avx512f, typename Batch::arch_type>;
#else
    false;
#endif

/// Bit i set where lane i of `m` is true: one movemask on SSE and AVX batches, the mask
/// register itself on AVX-512.
template <class Batch>
inline std::uint32_t mask_bits(const typename Batch::batch_bool_type& m) {
  using Arch = typename Batch::arch_type;
#if XSIMD_WITH_AVX512F
  if constexpr (kZmm<Batch>) {
    return std::uint32_t(static_cast<__mmask16>(m));
  } else
#endif
  if constexpr (Batch::size == 8 && std::is_base_of_v<xsimd::avx, Arch>) {
    return std::uint32_t(_mm256_movemask_ps(m));
  } else if constexpr (Batch::size == 4 && std::is_base_of_v<xsimd::sse2, Arch>) {
    return std::uint32_t(_mm_movemask_ps(m));
  } else {
    alignas(64) float lanes[Batch::size];
    xsimd::select(m, Batch(1.0f), Batch(0.0f)).store_aligned(lanes);
    std::uint32_t bits = 0;
    for (std::size_t i = 0; i < Batch::size; ++i) bits |= std::uint32_t(lanes[i] != 0.0f) << i;
    return bits;
  }
}

/// The smallest (Max false) or largest (Max true) lane of `b` (no NaN lanes): the two halves'
/// lanes compared in one SIMD step, down to 4 lanes, then those 4 in turn.
template <bool Max, class Batch>
inline float reduce_lanes(const Batch& b) {
  constexpr std::size_t n = Batch::size;
  alignas(64) float lanes[n];
  b.store_aligned(lanes);
  if constexpr (n > 4) {
    using Half = FloatN<int(n / 2)>;
    const Half lo = Half::load_aligned(lanes), hi = Half::load_aligned(lanes + n / 2);
    if constexpr (Max)
      return reduce_lanes<Max>(xsimd::max(lo, hi));
    else
      return reduce_lanes<Max>(xsimd::min(lo, hi));
  } else {
    float m = lanes[0];
    for (std::size_t i = 1; i < n; ++i) m = Max ? (lanes[i] > m ? lanes[i] : m) : (lanes[i] < m ? lanes[i] : m);
    return m;
  }
}

/// The smallest lane of `b` (no NaN lanes).
template <class Batch>
inline float reduce_min(const Batch& b) {
  return reduce_lanes<false>(b);
}

/// The largest lane of `b` (no NaN lanes).
template <class Batch>
inline float reduce_max(const Batch& b) {
  return reduce_lanes<true>(b);
}

/// `a > b ? a : b` lane by lane, so a NaN in `a` (a 0 * inf slab distance) gives `b`, and
/// (-0, +0) gives +0: exactly what x86's MAXPS computes, which xsimd::max(a, b) is on SSE2, AVX and
/// AVX-512. One instruction where the select takes a compare and a blend.
template <class Batch>
[[gnu::always_inline]] inline Batch max_or_second(const Batch& a, const Batch& b) {
#if XSIMD_WITH_AVX512F
  // GCC 12's _mm512_max_ps (xsimd's) passes an undefined register as the masked-off lanes and
  // -Wuninitialized reports it (GCC PR 105593); zero-masking with every lane on is the same VMAXPS.
  if constexpr (kZmm<Batch>)
    return _mm512_maskz_max_ps(__mmask16(0xFFFF), a, b);
  else
#endif
    return xsimd::max(a, b);
}

/// `a < b ? a : b` lane by lane (x86's MINPS; see max_or_second).
template <class Batch>
[[gnu::always_inline]] inline Batch min_or_second(const Batch& a, const Batch& b) {
#if XSIMD_WITH_AVX512F
  if constexpr (kZmm<Batch>)
    return _mm512_maskz_min_ps(__mmask16(0xFFFF), a, b);
  else
#endif
    return xsimd::min(a, b);
}

/// Index of the lowest set bit of a non-zero mask.
inline int first_lane(std::uint32_t bits) { return std::countr_zero(bits); }

}  // namespace accel::simd
