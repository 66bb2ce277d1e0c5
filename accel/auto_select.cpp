#include "auto_select.h"

#include "params_json.h"

namespace accel {

void to_json(nlohmann::json& j, const AutoParams& p) {
  j = {{"naive_max_prims", p.naive_max_prims}};
}

void from_json(const nlohmann::json& j, AutoParams& p) {
  KnobReader r("auto", j);
  r.read("naive_max_prims", p.naive_max_prims, 0, 1 << 30);
  r.finish();
}

AutoChoice choose_structure(const AutoParams& params, std::size_t primitives) {
  return primitives <= std::size_t(params.naive_max_prims) ? AutoChoice::Naive : AutoChoice::Bvh;
}

}  // namespace accel
