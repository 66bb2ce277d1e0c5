#pragma once
// Reader for Eric Haines' Neutral File Format (NFF), the format of the Standard Procedural
// Databases (SPD).
//
// Parsed by tokens, not lines, so an entity may span lines (`c` on one line or several). Maps:
//   b r g b                      -> Scene::background
//   v from/at/up/angle/hither/resolution -> Scene::camera; angle is the full field of view
//                                   (degrees), up need not be perpendicular to the view
//   l x y z [r g b]              -> PointLight; colour defaults to white. NFF lights have no
//                                   power: each gets the SPD relative intensity 1/(2 sqrt(n))
//                                   of n lights (SPD README: sqrt(n) / (2 n)), stored as the power
//                                   with which a white Lambertian surface at the look-at point,
//                                   facing the light, reflects that intensity as radiance
//                                   (power_w = 4 pi^2 d^2 / (2 sqrt(n)), d = distance to `at`).
//                                   The SPD renderer ignores power_w and uses the intensity
//                                   without falloff, as the SPD rules do.
//   f r g b Kd Ks Shine T ior    -> Material of type Nff (identical `f` lines share one);
//                                   ior 0 is legal and becomes 1 when T = 0
//   s x y z r                    -> Sphere; r < 0 keeps the sign: only the inside is visible
//   c bx by bz br ax ay az ar    -> Cone (no end caps); both radii < 0: inside visible
//   p n v1..vn                   -> Triangle when n = 3, else Polygon (convex or concave)
//   pp n (v, normal) x n         -> triangles with vertex normals (a fan when n > 3)
//   # ...                        -> comment to the end of the line
// Primitives before the first `f` get a white diffuse material.

#include "scene.h"
#include "scene_error.h"

#include <istream>
#include <string>
#include <string_view>

namespace tracer {

/// Parses NFF text; `name_for_errors` prefixes every error message (a file name). Returns a
/// finalized Scene that the JSON loader also accepts (the same rules: colours >= 0, polygons
/// that span a plane, numbers within float range). Throws SceneError, whose what() is one line
/// "<name>:<line>: <what is wrong>"; never crashes or hangs on truncated or garbled input.
Scene parse_nff(std::string_view text, const std::string& name_for_errors);

/// parse_nff of everything `in` holds, up to the scene-file size limit.
Scene load_nff(std::istream& in, const std::string& name_for_errors);

/// Reads the file at `path` (a regular file within input::kMaxSceneFileBytes, refused before
/// reading otherwise); errors are prefixed with `path`.
Scene load_nff(const std::string& path);

}  // namespace tracer
