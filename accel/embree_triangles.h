#pragma once
// Embree's own triangles as the peer on meshes: RTC_GEOMETRY_TYPE_TRIANGLE, Embree's BVH over its
// triangle leaves and Embree's ray-triangle routine. Its default build (Embree's own defaults:
// medium quality, not robust) is the bar users know; robust = true is RTC_SCENE_FLAG_ROBUST,
// Embree's watertight mode, and build_quality = high its SAH build with spatial splits. Checked
// against naive within a tolerance (the same triangle for >= 99.9% of rays, t within 1e-5
// relative), not bit for bit.
//
// attach_triangles, which tracer::attach_geometry calls for a scene of triangles only, builds the
// native scene (embree_native.h). The vertices are shared where the mesh shares them (equal
// positions become one vertex), as a mesh handed to Embree would be. A scene with other
// primitives stays user geometry, like `embree`.

#include "embree_native.h"
#include "triangle_shape.h"

#include <span>

namespace accel {

class EmbreeTriangles : public EmbreeNativePeer<EmbreeTrianglesParams> {
 public:
  static constexpr const char* kName = "embree_triangles";
  static constexpr const char* kSummary =
      "Embree 3's own triangles (RTC_GEOMETRY_TYPE_TRIANGLE) and its triangle routine: a peer checked "
      "within a tolerance";
  /// Embree tests the triangles of a triangle-only scene itself (attach_triangles).
  static constexpr const char* kNativeShapes = "triangles";

#if ACCELBENCH_HAVE_EMBREE
  EmbreeTriangles() = default;
  EmbreeTriangles(std::span<const Aabb> boxes, const Params& params, const BuildLimits& limits)
      : EmbreeNativePeer(boxes, params, limits, kName) {}

  /// Rebuilds the scene with `triangles` (triangles[i] is primitive i) as one Embree triangle
  /// mesh. Throws knobs::ConfigError on Embree's errors and the memory budget.
  void attach_triangles(std::span<const TriangleShape> triangles);
  static const char* stats_note() {
    return "embree_triangles: nodes, leaves, depth, sah_cost, nodes_visited, boxes_tested and (on its "
           "own triangles) prims_tested are not visible through Embree's API and are reported as 0; "
           "build_ms is Embree's triangle build (rtcCommitScene, not the user-geometry build before it "
           "nor the vertex sharing); memory_bytes is what Embree holds, its vertex and index buffers "
           "included";
  }
#endif
};

}  // namespace accel
