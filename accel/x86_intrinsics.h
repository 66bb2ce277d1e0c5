#pragma once
// <immintrin.h>, without GCC 12's false "'__Y' is used uninitialized" warnings: its AVX-512
// intrinsics (_mm512_min_ps, _mm512_max_ps, ...) pass _mm512_undefined_ps(), written
// `__m512 __Y = __Y;`, and GCC 12 warns at every call inlined into our kernels, some 90 times a
// build (the same report: google/highway#710). GCC checks the pragma state where a warning
// points, inside this header, so the warnings stay on for our own code. Included before xsimd by
// accel/simd.h and first in the precompiled header (CMakeLists.txt).

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#else
#include <immintrin.h>
#endif
