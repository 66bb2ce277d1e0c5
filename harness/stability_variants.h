#pragma once
// The variants of a scene the stability suite renders: the scene moved and scaled to the
// extremes, its camera looking exactly along each axis, its primitives snapped onto the split
// planes of the structures, duplicated, and paired with touching copies.

#include "tracer/scene.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace harness {

/// What a variant does to the scene.
enum class VariantKind : std::uint8_t {
  Base,        ///< The scene as it is.
  Translate,   ///< Everything moved by 10^exponent along `direction` (x, or the diagonal).
  Scale,       ///< Every length scaled by 10^exponent about the world origin.
  CameraAxis,  ///< The camera moved to look exactly along `direction`, at the same distance.
  Snapped,     ///< Primitives straddling a split plane moved so their centre lies on it.
  Duplicated,  ///< Every primitive (and plane) twice, exactly.
  Touching,    ///< Every bounded primitive plus a copy shifted by its width along x, touching it.
};

struct StabilityVariant {
  std::string name;                  ///< Unique name, e.g. translate_x_1e3, scale_1e-4, camera_-y.
  std::string group;                 ///< translate_x, translate_diag, scale, camera, snapped, ...
  VariantKind kind = VariantKind::Base;
  int exponent = 0;                  ///< k of the factor or distance 10^k (Translate, Scale).
  glm::dvec3 direction{0.0};         ///< Translate: per-axis unit steps; CameraAxis: view direction.
  /// Whether the variant should render the same image as the base scene (moved and scaled
  /// scenes, duplicates); the others change the picture and are compared with naive only.
  bool same_image = false;
};

/// The variant groups in order: base, translate_x, translate_diag, scale, camera, snapped,
/// duplicated, touching.
std::vector<std::string> variant_groups();

/// The variants of `selection`: a comma-separated list of group names and variant names, or
/// "all" (every variant), or "quick" (base, translate_x 1e2 and 1e4, scale 1e-4 and 1e4,
/// duplicated). The base variant is always first. Throws std::runtime_error naming `flag` and
/// the unknown entry.
std::vector<StabilityVariant> select_variants(const std::string& selection, const std::string& flag);

/// The scene of variant `v` of `base`.
tracer::Scene make_variant(const tracer::Scene& base, const StabilityVariant& v);

}  // namespace harness
