#include "whitted_params.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tracer {

namespace {

[[noreturn]] void fail(const std::string& knob, const std::string& what, const nlohmann::json& v) {
  throw std::invalid_argument("whitted: knob '" + knob + "' must be " + what + ", got " + v.dump());
}

long long integer(const nlohmann::json& v, const std::string& knob, long long lo, long long hi,
                  const std::string& range) {
  if (!v.is_number_integer()) fail(knob, "an integer " + range, v);
  if (v.is_number_unsigned() && v.get<std::uint64_t>() > std::uint64_t(hi)) fail(knob, range, v);
  const long long x = v.get<long long>();
  if (x < lo || x > hi) fail(knob, range, v);
  return x;
}

}  // namespace

RenderSettings WhittedParams::limits(const Scene& scene) const {
  RenderSettings r = scene.render;
  if (max_depth > 0) r.max_depth = max_depth;
  if (min_weight >= 0.0) r.min_weight = float(min_weight);
  return r;
}

int WhittedParams::samples_per_pixel(const Scene& scene) const {
  return spp > 0 ? spp : std::max(1, scene.camera.samples_per_pixel);
}

nlohmann::json to_json(const WhittedParams& p) {
  return {{"max_depth", p.max_depth},
          {"min_weight", p.min_weight},
          {"spp", p.spp},
          {"seed", p.seed},
          {"precision", p.precision == Precision::Double ? "double" : "float"}};
}

WhittedParams whitted_params_from_json(const nlohmann::json& j) {
  WhittedParams p;
  if (j.is_null()) return p;
  if (!j.is_object()) throw std::invalid_argument("whitted: knobs must be a JSON object, got " + j.dump());
  for (const auto& [key, v] : j.items()) {
    if (key == "max_depth") {
      p.max_depth = int(integer(v, key, 0, 1000, "in [1, 1000], or 0 for the scene's"));
    } else if (key == "min_weight") {
      if (!v.is_number()) fail(key, "a number in [0, 1], or negative for the scene's", v);
      p.min_weight = v.get<double>();
      if (!std::isfinite(p.min_weight) || p.min_weight > 1.0)
        fail(key, "in [0, 1], or negative for the scene's", v);
      if (p.min_weight < 0.0) p.min_weight = -1.0;
    } else if (key == "spp") {
      p.spp = int(integer(v, key, 0, 65536, "in [1, 65536], or 0 for the scene's"));
    } else if (key == "seed") {
      if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<long long>() >= 0))
        fail(key, "an integer in [0, 2^64-1]", v);
      p.seed = v.get<std::uint64_t>();
    } else if (key == "precision") {
      if (v != "float" && v != "double") fail(key, "\"float\" or \"double\"", v);
      p.precision = v == "double" ? Precision::Double : Precision::Float;
    } else {
      throw std::invalid_argument("whitted: unknown knob '" + key +
                                  "' (its knobs: max_depth, min_weight, spp, seed, precision)");
    }
  }
  return p;
}

}  // namespace tracer
