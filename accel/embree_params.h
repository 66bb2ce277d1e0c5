#pragma once
// Knobs of the Embree peers (embree_accel.h, embree_points.h, embree_triangles.h). Compiled whether or not Embree 3
// was found, so that the knob reference and the registry know them in every build.

#include "isa.h"
#include "knobs/knob_table.h"

#include <cstdint>

namespace accel {

/// Embree's BVH build quality.
enum class EmbreeQuality : std::uint8_t { Medium, High };

/// The instruction set Embree's kernels run at (its device config `isa=`).
enum class EmbreeIsa : std::uint8_t {
  Build,  ///< The level this build of accelbench targets (build_isa()): like for like.
  Cpu,    ///< Embree's own pick: the highest the CPU has.
  Sse2,
  Sse42,
  Avx,
  Avx2,
  Avx512,
};

/// Rays per Embree packet query (rtcIntersect4/8/16, rtcOccluded4/8/16).
enum class EmbreePacket : std::uint8_t {
  Auto,     ///< Embree's native width at its ISA: 16 at avx512, 8 at avx/avx2, 4 below.
  Lanes4,
  Lanes8,
  Lanes16,
};

/// Knobs of the Embree adapter.
struct EmbreeParams {
  /// Build quality: RTC_BUILD_QUALITY_MEDIUM or RTC_BUILD_QUALITY_HIGH (slower build, SAH splits).
  EmbreeQuality build_quality = EmbreeQuality::High;
  /// RTC_SCENE_FLAG_ROBUST: conservative box tests, so no primitive is culled by rounding.
  bool robust = true;
  /// Threads Embree's TBB builder may use; 0 = Embree's default (every core). 1, like the
  /// BVHs' build_threads, so that build times compare like for like.
  int build_threads = 1;
  /// Instruction set of Embree's kernels; one the CPU lacks is refused.
  EmbreeIsa isa = EmbreeIsa::Build;
  /// Rays per packet query of the packet traversals.
  EmbreePacket packet = EmbreePacket::Auto;

  /// Name, range, unit and doc line of every knob above.
  static const knobs::KnobTable<EmbreeParams>& knobs();
};

/// Knobs of embree_points: the same as the user-geometry adapter's, under its own name.
struct EmbreePointsParams : EmbreeParams {
  static const knobs::KnobTable<EmbreePointsParams>& knobs();
};

/// Knobs of embree_triangles: the adapter's, under its own name, with Embree's own defaults as
/// the defaults (RTC_BUILD_QUALITY_MEDIUM, no scene flags), the bar users know; robust = true is
/// its watertight mode, build_quality = high its SAH build with spatial splits.
struct EmbreeTrianglesParams : EmbreeParams {
  EmbreeTrianglesParams() {
    build_quality = EmbreeQuality::Medium;
    robust = false;
  }
  static const knobs::KnobTable<EmbreeTrianglesParams>& knobs();
};

/// The level `isa` stands for on a CPU with the levels `cpu` (Build and Cpu resolved).
Isa resolve_embree_isa(EmbreeIsa isa, IsaSet cpu);
/// Rays per packet query for `packet` at Embree's level `isa`: 4, 8 or 16.
int resolve_embree_packet(EmbreePacket packet, Isa isa);
/// Throws knobs::ConfigError "<owner>: knob 'isa' = ...", one line naming the level and the knob,
/// when `isa` asks for a level the CPU with the levels `cpu` lacks.
void check_embree_isa(EmbreeIsa isa, IsaSet cpu, const char* owner = "embree");

}  // namespace accel
