#include "whitted_params.h"

#include <algorithm>

namespace tracer {

RenderSettings WhittedParams::limits(const Scene& scene) const {
  RenderSettings r = scene.render;
  if (max_depth > 0) r.max_depth = max_depth;
  if (min_weight >= 0.0) r.min_weight = float(min_weight);
  return r;
}

int WhittedParams::samples_per_pixel(const Scene& scene) const {
  return spp > 0 ? spp : std::max(1, scene.camera.samples_per_pixel);
}

const knobs::KnobTable<WhittedParams>& WhittedParams::knobs() {
  using K = knobs::Knob<WhittedParams>;
  // max_depth and min_weight share one front reference, the scene at depth 64 with no weight
  // cut-off; its own truncation error is estimated by its difference from depth 48 (the light of
  // bounces 49-64 bounds that of all bounces past 64 while every 16 bounces carry at most half of
  // the 16 before). spp's reference is 2 x 1024 samples per pixel with independent jitter, at the
  // front's own depth and weight; its noise is estimated from the two halves. precision's is the
  // double render at the front's other knobs, so double has error 0 and float's error is its
  // distance from double; the reference's own rounding is not estimated (there is no wider type
  // to check it against), its floor reads 0.
  static constexpr const char* kDeepReference = R"({"max_depth": 64, "min_weight": 0})";
  static constexpr const char* kDeepCheck = R"({"max_depth": 48, "min_weight": 0})";
  static const knobs::KnobTable<WhittedParams> table(
      "whitted",
      {K::integer("max_depth", &WhittedParams::max_depth, 0, 1000, "levels",
                  "Recursion depth (camera ray = 1): lower cuts off reflected and refracted light; "
                  "0 = the scene's.")
           .front({"[1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64]", "", kDeepReference, kDeepCheck, false}),
       K::number("min_weight", &WhittedParams::min_weight, -1.0, 1.0, "",
                 "Paths whose weight falls below this are cut: higher is faster and darker; "
                 "negative = the scene's.")
           .front({"[0.3, 0.1, 0.03, 0.01, 0.003, 0.001, 0.0003, 0.0001, 0]", "", kDeepReference,
                   kDeepCheck, false}),
       K::integer("spp", &WhittedParams::spp, 0, 65536, "samples",
                  "Camera rays per pixel: more samples average away aliasing at edges; 0 = the "
                  "camera's.")
           .front({"[1, 2, 4, 8, 16, 32, 64]", "", R"({"spp": 1024})", "", true}),
       K::integer(knobs::kSeedKnob, &WhittedParams::seed, 0, ~0ull, "",
                  "Seed of the sub-pixel jitter; 0 = the fixed pattern of every earlier render."),
       precision_knob(&WhittedParams::precision)
           .front({R"(["float", "double"])", "", R"({"precision": "double"})", "", false}),
       // moller's error against the watertight render at the front's other knobs: the light
       // that leaks through shared edges.
       triangle_knob(&WhittedParams::triangle)
           .front({R"(["moller", "watertight"])", "", R"({"triangle": "watertight"})", "", false})});
  return table;
}

}  // namespace tracer
