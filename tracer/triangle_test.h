#pragma once
// Which ray/triangle routine the tracer runs: the `triangle` knob of every integrator.
//
// Watertight (Woop, Benthin and Wald 2013; pbrt-v4's IntersectTriangle) decides each edge with
// the same arithmetic for the two triangles that share it, so a ray through a shared edge or
// vertex of a closed mesh hits one of them. Moller-Trumbore is faster and decides each triangle
// alone, so such rays can slip between two neighbours. Both give the same hits away from edges.

#include "accel/triangle_shape.h"
#include "knobs/knob_table.h"

#include <cstdint>

namespace tracer {

/// The ray/triangle routine of a render; defined beside the structures' triangles, whose SIMD
/// leaves run the same routine (accel/triangle_hit.h).
using accel::TriangleTest;

/// The name of the knob that chooses it (every integrator has one).
inline constexpr const char* kTriangleKnob = "triangle";

/// Its spelling as a knob value.
inline const char* triangle_test_name(TriangleTest t) {
  return t == TriangleTest::Moller ? "moller" : "watertight";
}

/// The `triangle` knob of an integrator whose parameter struct P stores it in `member`. As a
/// front, moller is studied against the watertight render (the knob's error is the light that
/// leaks through edges; its gain is the time saved).
template <class P>
knobs::Knob<P> triangle_knob(TriangleTest P::*member) {
  return knobs::Knob<P>::choice(kTriangleKnob, member,
                                {{triangle_test_name(TriangleTest::Watertight), TriangleTest::Watertight},
                                 {triangle_test_name(TriangleTest::Moller), TriangleTest::Moller}},
                                "Ray/triangle routine: watertight (Woop-Benthin-Wald, never lets a ray "
                                "through a shared edge) or moller (Moller-Trumbore, faster, can leak).")
      .shorthand();
}

}  // namespace tracer
