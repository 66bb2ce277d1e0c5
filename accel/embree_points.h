#pragma once
// Embree's own spheres as a second peer: RTC_GEOMETRY_TYPE_SPHERE_POINT, so Embree's traversal
// and Embree's ray-sphere routine, with no callback per primitive. Checked against naive within a
// tolerance (the same sphere for >= 99.9% of rays, t within 1e-5 relative), not bit for bit.
//
// attach_spheres, which tracer::attach_geometry calls for a scene of spheres only, builds the
// native scene that every query uses from then on (embree_native.h). A scene with other
// primitives stays user geometry, like `embree`.

#include "embree_native.h"
#include "sphere_hit.h"

#include <span>

namespace accel {

class EmbreePoints : public EmbreeNativePeer<EmbreePointsParams> {
 public:
  static constexpr const char* kName = "embree_points";
  static constexpr const char* kSummary =
      "Embree 3's own spheres (RTC_GEOMETRY_TYPE_SPHERE_POINT) and its sphere routine: a peer checked "
      "within a tolerance";
  /// Embree tests the spheres of a sphere-only scene itself (attach_spheres).
  static constexpr const char* kNativeShapes = "spheres";

#if ACCELBENCH_HAVE_EMBREE
  EmbreePoints() = default;
  EmbreePoints(std::span<const Aabb> boxes, const Params& params, const BuildLimits& limits)
      : EmbreeNativePeer(boxes, params, limits, kName) {}

  /// Rebuilds the scene with `spheres` (spheres[i] is primitive i) as Embree's sphere points.
  /// Throws knobs::ConfigError on Embree's errors and the memory budget.
  void attach_spheres(std::span<const SphereShape> spheres);
  static const char* stats_note() {
    return "embree_points: nodes, leaves, depth, sah_cost, nodes_visited, boxes_tested and (on its own "
           "spheres) prims_tested are not visible through Embree's API and are reported as 0; build_ms "
           "is the sphere-point build (the user-geometry build over the boxes before it is not counted)";
  }
#endif
};

}  // namespace accel
