#pragma once
// The scalar type of the tracer's geometry: float for rendering, double for the reference.
//
// Scenes are stored in float. Every primitive routine, hit point, offset, camera ray and
// integrator is written once as a template on the scalar type T and instantiated for float (the
// renderer, unchanged) and double (the naive reference, RenderKnobs precision "double"), which
// traces the same float scene with double arithmetic, so that the float tracer's own error can
// be told from the error of storing the scene in float.

#include "accel/geometry.h"
#include "knobs/knob_table.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>
#include <type_traits>

namespace tracer {

/// Floating-point type of the tracer's geometric arithmetic.
enum class Precision : std::uint8_t { Float, Double };

/// The name of the knob that chooses the precision (every integrator that has one: the stability
/// suite renders each scene at both).
inline constexpr const char* kPrecisionKnob = "precision";

/// A precision's spelling as a knob value: "float" or "double".
inline const char* precision_name(Precision p) { return p == Precision::Double ? "double" : "float"; }

/// The `precision` knob of an integrator whose parameter struct P stores it in `member`.
template <class P>
knobs::Knob<P> precision_knob(Precision P::*member) {
  return knobs::Knob<P>::choice(kPrecisionKnob, member,
                                {{precision_name(Precision::Float), Precision::Float},
                                 {precision_name(Precision::Double), Precision::Double}},
                                "Arithmetic of the whole tracer: double (the naive loop over every primitive in "
                                "double; the structure is not used) is the reference, float traces through the "
                                "structure and is faster.")
      .shorthand();
}

template <class T>
using Vec3T = glm::vec<3, T>;

/// A ray in double precision, member for member like accel::Ray.
struct RayD {
  glm::dvec3 org{0.0};                                    ///< Origin, world units.
  double tmin = 0.0;                                      ///< Nearest accepted hit distance.
  glm::dvec3 dir{0.0, 0.0, 1.0};                          ///< Direction; need not be unit length.
  double tmax = std::numeric_limits<double>::infinity();  ///< Farthest accepted hit distance.
};

/// The ray of scalar type T: accel::Ray for float, RayD for double.
template <class T>
using RayT = std::conditional_t<std::is_same_v<T, double>, RayD, accel::Ray>;

/// The scalar type of a ray type (float for accel::Ray, double for RayD).
template <class R>
using ScalarOf = std::remove_cvref_t<decltype(R::tmin)>;

/// +infinity of T: the distance of a miss.
template <class T>
inline constexpr T kInfinityOf = std::numeric_limits<T>::infinity();

}  // namespace tracer
