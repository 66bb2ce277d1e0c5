// Issue 3's image check: the paper's spheres8000 scene (Whitted: shadow, mirror and glass rays)
// renders bit-identical, with identical ray counts, through every structure and knob setting.

#include "accel/accel.h"
#include "scenes_gen/generators.h"
#include "tracer/render.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace {

struct Variant {
  std::string accel;
  nlohmann::json params;
};

std::vector<Variant> variants() {
  std::vector<Variant> out;
  for (const std::string& name : accel::accel_names()) {
    if (name == "naive" || !accel::accel_built(name)) continue;
    out.push_back({name, nlohmann::json::object()});
  }
  for (const char* placement : {"leaves", "every_level"}) {
    out.push_back({"octree", {{"placement", placement}, {"max_depth", 5}, {"max_leaf_size", 2}}});
    for (const char* split : {"midpoint", "sah"})
      out.push_back({"kdtree", {{"placement", placement}, {"split", split}, {"max_leaf_size", 1}}});
  }
  out.push_back({"bvh", {{"max_leaf_size", 1}, {"bins", 8}}});
  return out;
}

TEST(AccelImage, Spheres8000IsBitIdenticalThroughEveryStructure) {
  const tracer::Scene scene = scenes_gen::generate("spheres8000", {});
  const std::vector<accel::Aabb> boxes = scene.geometry.primitive_bounds();
  tracer::RenderOptions options;
  options.width = 96;
  options.height = 72;
  options.threads = 2;

  const tracer::RenderResult reference =
      tracer::render(scene, accel::make_accel("naive", {}, boxes), options,
                     tracer::whitted_integrator());
  ASSERT_GT(reference.rays.eye_hits, 0u);
  ASSERT_GT(reference.rays.shadow, 0u);

  for (const Variant& v : variants()) {
    SCOPED_TRACE(v.accel + " " + v.params.dump());
    const tracer::RenderResult result =
        tracer::render(scene, accel::make_accel(v.accel, v.params, boxes), options,
                       tracer::whitted_integrator());
    EXPECT_EQ(result.image.content_hash(), reference.image.content_hash());
    EXPECT_TRUE(result.image == reference.image);
    EXPECT_TRUE(result.rays == reference.rays);
  }
}

}  // namespace
