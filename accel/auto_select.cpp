#include "auto_select.h"

#include "accel.h"

namespace accel {

const knobs::KnobTable<AutoParams>& AutoParams::knobs() {
  using K = knobs::Knob<AutoParams>;
  static const knobs::KnobTable<AutoParams> table(
      "auto", {K::integer("naive_max_prims", &AutoParams::naive_max_prims, 0, 1 << 30, "primitives",
                          "Scenes with at most this many primitives use naive; larger ones a tree.")
                   .probes({0, 1 << 30})});
  return table;
}

AutoChoice choose_structure(const AutoParams& params, std::size_t primitives) {
  return primitives <= std::size_t(params.naive_max_prims) ? AutoChoice::Naive : AutoChoice::Tree;
}

AnyAccel AutoSelect::select(std::span<const Aabb> boxes, const AutoParams& params, const BuildLimits& limits) {
  AutoParams::knobs().validate(params);
  AnyAccel chosen;
  if (choose_structure(params, boxes.size()) == AutoChoice::Naive)
    chosen = Naive(boxes, NaiveParams{}, limits);
  else
    chosen = Bvh8(boxes, Bvh8::Params{}, limits);
  chosen.selected_by = {{"structure", kName}, {"params", AutoParams::knobs().to_json(params)}};
  return chosen;
}

}  // namespace accel
