#pragma once
// Knobs of the Embree adapter (embree_accel.h). Compiled whether or not Embree 3 was found, so
// that the knob reference and the registry know them in every build.

#include "knob_table.h"

#include <cstdint>

namespace accel {

/// Embree's BVH build quality.
enum class EmbreeQuality : std::uint8_t { Medium, High };

/// Knobs of the Embree adapter.
struct EmbreeParams {
  /// Build quality: RTC_BUILD_QUALITY_MEDIUM or RTC_BUILD_QUALITY_HIGH (slower build, SAH splits).
  EmbreeQuality build_quality = EmbreeQuality::High;
  /// RTC_SCENE_FLAG_ROBUST: conservative box tests, so no primitive is culled by rounding.
  bool robust = true;
  /// Threads Embree's TBB builder may use; 0 = Embree's default (every core). The other
  /// builders are single-threaded, so 1 keeps build times comparable.
  int build_threads = 1;

  /// Name, range, unit and doc line of every knob above.
  static const KnobTable<EmbreeParams>& knobs();
};

}  // namespace accel
