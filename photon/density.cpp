#include "density.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace photon {

namespace {
constexpr std::pair<const char*, DensityFilter> kFilters[] = {
    {"box", DensityFilter::Box},
    {"cone", DensityFilter::Cone},
    {"biweight", DensityFilter::Biweight},
};
}  // namespace

std::string_view name_of(DensityFilter f) {
  for (const auto& [name, filter] : kFilters)
    if (filter == f) return name;
  return "?";
}

std::vector<std::pair<std::string, DensityFilter>> density_filter_choices() {
  std::vector<std::pair<std::string, DensityFilter>> out;
  for (const auto& [name, filter] : kFilters) out.emplace_back(name, filter);
  return out;
}

const knobs::KnobTable<DensityParams>& DensityParams::knobs() {
  using K = knobs::Knob<DensityParams>;
  static const knobs::KnobTable<DensityParams> table(
      "density", {K::choice("filter", &DensityParams::filter, density_filter_choices(),
                            "Density-estimation kernel: box, the paper's cone, or biweight.")
                      .variant(),
                  K::number("cone_k", &DensityParams::cone_k, 1.0, 1e6, "",
                            "Cone filter constant: weight 1 - d / (cone_k r); 1 is the sharpest cone.")});
  return table;
}

void validate(const DensityParams& p) { DensityParams::knobs().validate(p); }

float estimate_radius2(const Neighbors& found) {
  if (found.empty()) return 0.0f;
  const float kth = found.max_d2();
  if (found.full() && kth > 0.0f) return kth;
  if (std::isfinite(found.max_radius2())) return found.max_radius2();
  return found.full() ? 0.0f : kth;
}

Color flux_density(const PhotonMap& map, Neighbors& found, const DensityParams& params,
                   const Vec3& normal) {
  validate(params);
  const float r2 = estimate_radius2(found);
  if (!(r2 > 0.0f) || !std::isfinite(r2)) return Color(0.0f);
  found.sort([&](std::uint32_t slot) { return map.original_index(slot); });
  const bool cull = normal.x != 0.0f || normal.y != 0.0f || normal.z != 0.0f;
  const double pi = std::numbers::pi;
  // Sums in double: the order is fixed, and k photons of very different power lose nothing.
  double sum[3] = {0.0, 0.0, 0.0};
  double norm = pi * double(r2);
  const double r = std::sqrt(double(r2));
  const double cone_k = params.cone_k;
  if (params.filter == DensityFilter::Cone) norm *= 1.0 - 2.0 / (3.0 * cone_k);
  for (const Neighbor& nb : found.items()) {
    const Photon& p = map.photon(nb.slot);
    if (cull && !p.arrives_from_side_of(normal)) continue;
    double w = 1.0;
    switch (params.filter) {
      case DensityFilter::Box:
        break;
      case DensityFilter::Cone:
        w = std::max(0.0, 1.0 - std::sqrt(double(nb.d2)) / (cone_k * r));
        break;
      case DensityFilter::Biweight: {
        const double s = 1.0 - std::min(1.0, double(nb.d2) / double(r2));
        w = 3.0 * s * s;
        break;
      }
    }
    const Color c = p.power();
    sum[0] += w * c.x;
    sum[1] += w * c.y;
    sum[2] += w * c.z;
  }
  return Color(float(sum[0] / norm), float(sum[1] / norm), float(sum[2] / norm));
}

}  // namespace photon
