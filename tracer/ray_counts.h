#pragma once
// How many rays of each kind a render traced; gathered on every render (one add per ray).

#include <nlohmann/json.hpp>

#include <cstdint>

namespace tracer {

struct RayCounts {
  std::uint64_t eye = 0;         ///< Camera (primary) rays traced.
  std::uint64_t eye_hits = 0;    ///< Camera rays that hit a primitive.
  std::uint64_t reflection = 0;  ///< Reflected rays traced (mirrors, dielectrics, TIR).
  std::uint64_t refraction = 0;  ///< Refracted (transmitted) rays traced.
  std::uint64_t shadow = 0;      ///< Shadow rays traced towards lights.
  std::uint64_t gather = 0;      ///< Final-gather rays traced from diffuse surfaces (photon mapping).
  std::uint64_t photon = 0;      ///< Photon rays traced from the lights and between bounces.

  /// Every ray traced, shadow, gather and photon rays included.
  std::uint64_t total() const { return eye + reflection + refraction + shadow + gather + photon; }

  RayCounts& operator+=(const RayCounts& o) {
    eye += o.eye;
    eye_hits += o.eye_hits;
    reflection += o.reflection;
    refraction += o.refraction;
    shadow += o.shadow;
    gather += o.gather;
    photon += o.photon;
    return *this;
  }
  friend bool operator==(const RayCounts&, const RayCounts&) = default;
};

inline void to_json(nlohmann::json& j, const RayCounts& c) {
  j = {{"eye", c.eye},
       {"eye_hits", c.eye_hits},
       {"reflection", c.reflection},
       {"refraction", c.refraction},
       {"shadow", c.shadow},
       {"gather", c.gather},
       {"photon", c.photon},
       {"total", c.total()}};
}

inline void from_json(const nlohmann::json& j, RayCounts& c) {
  j.at("eye").get_to(c.eye);
  j.at("eye_hits").get_to(c.eye_hits);
  j.at("reflection").get_to(c.reflection);
  j.at("refraction").get_to(c.refraction);
  j.at("shadow").get_to(c.shadow);
  c.gather = j.value("gather", std::uint64_t(0));  // absent in files from before photon mapping
  c.photon = j.value("photon", std::uint64_t(0));
}

}  // namespace tracer
