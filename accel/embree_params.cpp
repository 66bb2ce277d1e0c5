#include "embree_params.h"

namespace accel {

const KnobTable<EmbreeParams>& EmbreeParams::knobs() {
  using K = Knob<EmbreeParams>;
  static const KnobTable<EmbreeParams> table(
      "embree",
      {K::choice("build_quality", &EmbreeParams::build_quality,
                 {{"medium", EmbreeQuality::Medium}, {"high", EmbreeQuality::High}},
                 "RTC_BUILD_QUALITY_MEDIUM or _HIGH (slower build, SAH splits)."),
       K::boolean("robust", &EmbreeParams::robust,
                  "RTC_SCENE_FLAG_ROBUST: conservative box tests, so no primitive is culled by rounding."),
       K::integer("build_threads", &EmbreeParams::build_threads, 0, 1024, "threads",
                  "Threads Embree's builder may use; 0 = every core (the other builders use one).")
           .probes({0, 1})});
  return table;
}

}  // namespace accel
