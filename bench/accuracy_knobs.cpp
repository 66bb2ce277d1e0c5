#include "accuracy_knobs.h"

#include <array>

namespace bench {

namespace {

// Whitted: max_depth and min_weight share one reference, the scene at depth 64 with no weight
// cut-off; its own truncation error is estimated by its difference from depth 48 (the light of
// bounces 49-64 bounds that of all bounces past 64 while every 16 bounces carry at most half of
// the 16 before). spp's reference is 2 x 1024 samples per pixel with independent jitter, at the
// front's own depth and weight; its noise is estimated from the two halves.
// The photon knobs' reference: 256 passes of 50,000 photons per map (12.8 million per map and
// half), pilot-pass initial radii, alpha 2/3.
constexpr const char* kPpmReference = R"({"passes": 256, "photons_per_pass": 50000})";

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
    // Float against double (the double-precision reference tracer): the reference is the double render at
    // the front's own other knobs, so the double point has error 0 and float's error is its
    // distance from double. The reference's own rounding (relative 2^-53 per operation) is not
    // estimated: there is no wider type to check it against; its floor reads 0.
    AccuracyKnob{"whitted", "precision", "",
                 "arithmetic of the whole tracer: double is the reference, float is faster",
                 R"(["float", "double"])", "", R"({"precision": "double"})", "", false},
    // The photon-mapping integrator's knobs all share one reference that has none of them:
    // progressive photon mapping (photon/ppm_integrator.h) run long, two halves with
    // independent seeds, its noise estimated from the halves and its remaining bias from a
    // render with 1/8 of its passes (group_reference in fronts.cpp). Its camera paths are the
    // photon integrator's (Whitted's), so it converges to what the photon integrator estimates.
    AccuracyKnob{"photon", "global_photons", "photons",
                 "photons in the global map (indirect light): more is less noise, less blur, slower",
                 "[1000, 3000, 10000, 30000, 100000, 300000, 1000000]", "ppm", kPpmReference, "", true},
    AccuracyKnob{"photon", "caustic_photons", "photons",
                 "photons in the caustic map (light focused by mirrors and glass): more is sharper",
                 "[1000, 3000, 10000, 30000, 100000, 300000, 1000000]", "ppm", kPpmReference, "", true},
    AccuracyKnob{"photon", "k", "photons",
                 "photons per density estimate: more is less noise and more blur",
                 "[1, 2, 5, 10, 20, 50, 100, 200, 500]", "ppm", kPpmReference, "", true},
    AccuracyKnob{"photon", "cone_k", "",
                 "cone filter constant (filter cone): lower weights near photons more, sharper edges",
                 "[1, 1.1, 1.5, 2, 3, 5, 10]", "ppm", kPpmReference, "", true},
    AccuracyKnob{"photon", "max_radius", "world units",
                 "largest gather radius: smaller cuts sparse estimates short (darker, faster)",
                 "[0.01, 0.03, 0.1, 0.3, 1, 3]", "ppm", kPpmReference, "", true},
    AccuracyKnob{"photon", "final_gather_rays", "rays",
                 "final-gather rays per diffuse hit (0: read the global map directly)",
                 "[0, 1, 4, 16, 64, 256]", "ppm", kPpmReference, "", true},
    // Progressive photon mapping itself, for its convergence (error against photons traced):
    // the same recipe with 4x the passes of the longest value as the reference.
    AccuracyKnob{"ppm", "passes", "passes",
                 "photon passes (each photons_per_pass per map): error falls as N^-1/3 in RMSE",
                 "[1, 2, 4, 8, 16, 32, 64]", "", R"({"passes": 256})", "", true},
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
