#pragma once
// Floating-point rounding bounds and one-ulp steps, for float and double (pbrt-v4, ch. 6.8).

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace tracer {

/// Bound on the relative rounding error of n operations in T: n u / (1 - n u), where
/// u = epsilon / 2 is T's unit roundoff (pbrt's gamma(n)).
template <class T>
constexpr T rounding_gamma(int n) {
  constexpr T u = std::numeric_limits<T>::epsilon() * T(0.5);
  return (T(n) * u) / (T(1) - T(n) * u);
}

/// The smallest value of T above v; +0 and -0 both step to the smallest positive subnormal,
/// +inf and NaN stay as they are.
template <class T>
T next_up(T v) {
  static_assert(std::is_floating_point_v<T>);
  using Bits = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
  if (std::isinf(v) && v > T(0)) return v;
  if (std::isnan(v)) return v;
  if (v == T(0)) v = T(0);  // -0 and +0 alike
  Bits bits = std::bit_cast<Bits>(v);
  bits = v >= T(0) ? bits + 1 : bits - 1;
  return std::bit_cast<T>(bits);
}

/// The largest value of T below v; +0 and -0 both step to the smallest negative subnormal,
/// -inf and NaN stay as they are.
template <class T>
T next_down(T v) {
  return -next_up(-v);
}

}  // namespace tracer
