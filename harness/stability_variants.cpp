#include "harness/stability_variants.h"

#include "accel/kdtree.h"
#include "accel/octree.h"
#include "tracer/scene_transform.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace harness {

namespace {

/// "1e3", "1e-4".
std::string power_name(int k) { return "1e" + std::to_string(k); }

std::vector<StabilityVariant> all_variants() {
  std::vector<StabilityVariant> out;
  out.push_back({"base", "base", VariantKind::Base, 0, glm::dvec3(0.0), true});
  for (int k = 1; k <= 6; ++k)
    out.push_back({"translate_x_" + power_name(k), "translate_x", VariantKind::Translate, k,
                   glm::dvec3(1.0, 0.0, 0.0), true});
  for (int k = 1; k <= 6; ++k)
    out.push_back({"translate_diag_" + power_name(k), "translate_diag", VariantKind::Translate, k,
                   glm::dvec3(1.0, -1.0, 1.0), true});
  for (int k = -6; k <= 6; ++k)
    if (k != 0)
      out.push_back({"scale_" + power_name(k), "scale", VariantKind::Scale, k, glm::dvec3(0.0), true});
  const char* axes[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  for (int i = 0; i < 6; ++i) {
    glm::dvec3 d(0.0);
    d[i / 2] = i % 2 == 0 ? 1.0 : -1.0;
    out.push_back({std::string("camera_") + axes[i], "camera", VariantKind::CameraAxis, 0, d, false});
  }
  out.push_back({"snapped", "snapped", VariantKind::Snapped, 0, glm::dvec3(0.0), false});
  out.push_back({"duplicated", "duplicated", VariantKind::Duplicated, 0, glm::dvec3(0.0), true});
  out.push_back({"touching", "touching", VariantKind::Touching, 0, glm::dvec3(0.0), false});
  return out;
}

/// The split planes (axis, position) of the midpoint kd-tree and the first four levels of the
/// octree's cell mid-planes, over the scene's primitive bounds.
std::vector<std::pair<int, float>> split_planes(const tracer::Geometry& g) {
  std::vector<std::pair<int, float>> planes;
  const std::vector<accel::Aabb> boxes = g.primitive_bounds();
  if (boxes.empty()) return planes;
  const accel::KdTree kd(boxes);
  for (const accel::KdNode& n : kd.nodes())
    if (!n.is_leaf()) planes.emplace_back(n.axis(), n.split());
  const accel::Octree oct(boxes);
  const accel::Aabb& cell = oct.root_cell();
  for (int level = 1; level <= 4; ++level) {
    const int cells = 1 << level;
    for (int a = 0; a < 3; ++a)
      for (int i = 1; i < cells; i += 2)  // the mid-planes new at this level
        planes.emplace_back(a, cell.lo[a] + (cell.hi[a] - cell.lo[a]) * float(i) / float(cells));
  }
  return planes;
}

/// Moves every bounded primitive whose box straddles a split plane so that its centre lies on
/// the nearest such plane.
void snap_onto_split_planes(tracer::Geometry& g) {
  const auto planes = split_planes(g);
  const std::vector<accel::Aabb> boxes = g.primitive_bounds();
  for (std::uint32_t id = 0; id < g.bounded_count(); ++id) {
    const glm::dvec3 c = tracer::primitive_centre(g, id);
    double best = -1.0;
    glm::dvec3 delta(0.0);
    for (const auto& [axis, value] : planes) {
      if (!(boxes[id].lo[axis] <= value && value <= boxes[id].hi[axis])) continue;
      const double d = std::abs(double(value) - c[axis]);
      if (best < 0.0 || d < best) {
        best = d;
        delta = glm::dvec3(0.0);
        delta[axis] = double(value) - c[axis];
      }
    }
    if (best > 0.0) tracer::move_primitive(g, id, delta);
  }
}

/// Width of bounded primitive `id` along x (its exact box, not rounded outward).
double width_x(const tracer::Geometry& g, std::uint32_t id) {
  switch (g.kind_of(id)) {
    case tracer::PrimitiveKind::Sphere:
      return 2.0 * std::abs(double(g.spheres[id - g.first_id[0]].radius));
    case tracer::PrimitiveKind::Triangle: {
      const accel::Aabb b = tracer::bounds(g.triangles[id - g.first_id[1]]);
      return double(b.hi.x) - double(b.lo.x);
    }
    case tracer::PrimitiveKind::Box: {
      const tracer::Box& b = g.boxes[id - g.first_id[2]];
      return double(b.hi.x) - double(b.lo.x);
    }
    case tracer::PrimitiveKind::Cone: {
      const accel::Aabb b = tracer::bounds(g.cones[id - g.first_id[3]]);
      return double(b.hi.x) - double(b.lo.x);
    }
    case tracer::PrimitiveKind::Polygon: {
      const accel::Aabb b = tracer::bounds(g.polygons[id - g.first_id[4]], g.polygon_vertices.data());
      return double(b.hi.x) - double(b.lo.x);
    }
    case tracer::PrimitiveKind::Count:
      break;
  }
  return 0.0;
}

void look_along(tracer::Camera& cam, const glm::dvec3& dir) {
  const glm::dvec3 at(cam.look_at), from(cam.position);
  const double dist = glm::length(at - from);
  cam.position = tracer::Vec3(at - dist * dir);
  // The scene's up, unless it is (nearly) the view direction: then the next axis round.
  glm::dvec3 up(cam.up);
  if (std::abs(glm::dot(glm::normalize(up), dir)) > 0.99)
    up = std::abs(dir.y) > 0.5 ? glm::dvec3(0.0, 0.0, 1.0) : glm::dvec3(0.0, 1.0, 0.0);
  cam.up = tracer::Vec3(up);
}

}  // namespace

std::vector<std::string> variant_groups() {
  return {"base", "translate_x", "translate_diag", "scale", "camera", "snapped", "duplicated",
          "touching"};
}

std::vector<StabilityVariant> select_variants(const std::string& selection, const std::string& flag) {
  const std::vector<StabilityVariant> all = all_variants();
  std::vector<bool> chosen(all.size(), false);
  chosen[0] = true;  // base
  std::size_t start = 0;
  while (start <= selection.size()) {
    const std::size_t comma = std::min(selection.find(',', start), selection.size());
    const std::string item = selection.substr(start, comma - start);
    start = comma + 1;
    if (item.empty()) continue;
    bool matched = false;
    for (std::size_t i = 0; i < all.size(); ++i) {
      const bool quick = item == "quick" &&
                         (all[i].name == "translate_x_1e2" || all[i].name == "translate_x_1e4" ||
                          all[i].name == "scale_1e-4" || all[i].name == "scale_1e4" ||
                          all[i].name == "duplicated");
      if (item == "all" || quick || all[i].group == item || all[i].name == item) {
        chosen[i] = true;
        matched = true;
      }
    }
    if (!matched && item != "quick") {
      std::string groups;
      for (const std::string& g : variant_groups()) groups += (groups.empty() ? "" : ", ") + g;
      throw std::runtime_error(flag + ": unknown variant '" + item + "' (groups: " + groups +
                               "; or a variant name such as translate_x_1e3, scale_1e-4, " +
                               "camera_-y; or all, quick)");
    }
  }
  std::vector<StabilityVariant> out;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (chosen[i]) out.push_back(all[i]);
  return out;
}

tracer::Scene make_variant(const tracer::Scene& base, const StabilityVariant& v) {
  tracer::Scene scene = base;
  switch (v.kind) {
    case VariantKind::Base:
      break;
    case VariantKind::Translate:
      tracer::translate_scene(scene, std::pow(10.0, v.exponent) * v.direction);
      break;
    case VariantKind::Scale:
      tracer::scale_scene(scene, std::pow(10.0, v.exponent));
      break;
    case VariantKind::CameraAxis:
      look_along(scene.camera, v.direction);
      break;
    case VariantKind::Snapped:
      snap_onto_split_planes(scene.geometry);
      break;
    case VariantKind::Duplicated:
      tracer::append_copies(scene.geometry,
                            std::vector<glm::dvec3>(scene.geometry.bounded_count(), glm::dvec3(0.0)),
                            true);
      break;
    case VariantKind::Touching: {
      std::vector<glm::dvec3> shifts(scene.geometry.bounded_count());
      for (std::uint32_t id = 0; id < shifts.size(); ++id)
        shifts[id] = glm::dvec3(width_x(scene.geometry, id), 0.0, 0.0);
      tracer::append_copies(scene.geometry, shifts, false);
      break;
    }
  }
  return scene;
}

}  // namespace harness
