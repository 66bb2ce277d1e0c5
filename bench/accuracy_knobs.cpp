#include "accuracy_knobs.h"

#include <array>

namespace bench {

namespace {

// Whitted: max_depth and min_weight share one reference, the scene at depth 64 with no weight
// cut-off; its own truncation error is estimated by its difference from depth 48 (the light of
// bounces 49-64 bounds that of all bounces past 64 while every 16 bounces carry at most half of
// the 16 before). spp's reference is 2 x 1024 samples per pixel with independent jitter, at the
// front's own depth and weight; its noise is estimated from the two halves.
constexpr std::array kKnobs = {
    AccuracyKnob{"whitted", "max_depth", "levels",
                 "recursion depth (camera ray = 1): lower cuts off reflected and refracted light",
                 "[1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64]", "",
                 R"({"max_depth": 64, "min_weight": 0})", R"({"max_depth": 48, "min_weight": 0})",
                 false},
    AccuracyKnob{"whitted", "min_weight", "",
                 "paths whose weight falls below this are cut: higher is faster and darker",
                 "[0.3, 0.1, 0.03, 0.01, 0.003, 0.001, 0.0003, 0.0001, 0]", "",
                 R"({"max_depth": 64, "min_weight": 0})", R"({"max_depth": 48, "min_weight": 0})",
                 false},
    AccuracyKnob{"whitted", "spp", "samples",
                 "camera rays per pixel: more samples average away aliasing at edges",
                 "[1, 2, 4, 8, 16, 32, 64]", "", R"({"spp": 1024})", "", true},
};

}  // namespace

std::span<const AccuracyKnob> accuracy_knobs() { return kKnobs; }

const AccuracyKnob* find_accuracy_knob(std::string_view integrator, std::string_view knob) {
  for (const AccuracyKnob& k : kKnobs)
    if (k.integrator == integrator && k.knob == knob) return &k;
  return nullptr;
}

std::string accuracy_knob_names(std::string_view integrator) {
  std::string s;
  for (const AccuracyKnob& k : kKnobs)
    if (k.integrator == integrator) s += (s.empty() ? "" : ", ") + std::string(k.knob);
  return s;
}

std::vector<nlohmann::json> default_values(const AccuracyKnob& k) {
  const nlohmann::json v = nlohmann::json::parse(k.values);
  return {v.begin(), v.end()};
}

}  // namespace bench
