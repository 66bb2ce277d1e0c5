#include "embree_params.h"

#include "build_threads.h"

#include <string>
#include <vector>

namespace accel {

namespace {

/// The knobs of every Embree peer, for the parameter struct P (EmbreeParams or a struct derived
/// from it); the members are EmbreeParams's.
template <class P>
std::vector<knobs::Knob<P>> embree_knobs() {
  using K = knobs::Knob<P>;
  return {K::choice("build_quality", static_cast<EmbreeQuality P::*>(&P::build_quality),
                    {{"medium", EmbreeQuality::Medium}, {"high", EmbreeQuality::High}},
                    "RTC_BUILD_QUALITY_MEDIUM or _HIGH (slower build, SAH splits)."),
          K::boolean("robust", static_cast<bool P::*>(&P::robust),
                     "RTC_SCENE_FLAG_ROBUST: conservative box tests, so no primitive is culled by rounding."),
          K::integer(kBuildThreadsKnob, static_cast<int P::*>(&P::build_threads), 0, 1024, "threads",
                     "Threads Embree's TBB builder may use; 0 = every core (the BVHs' knob of the same name).")
              .probes({0, 1}),
          K::choice("isa", static_cast<EmbreeIsa P::*>(&P::isa),
                    {{"build", EmbreeIsa::Build},
                     {"cpu", EmbreeIsa::Cpu},
                     {"sse2", EmbreeIsa::Sse2},
                     {"sse4.2", EmbreeIsa::Sse42},
                     {"avx", EmbreeIsa::Avx},
                     {"avx2", EmbreeIsa::Avx2},
                     {"avx512", EmbreeIsa::Avx512}},
                    "Embree's instruction set: `build` = the one this build targets (like for like), "
                    "`cpu` = the highest the CPU has; a level the CPU lacks is refused.")
              .crossed()
              .probes({"sse2", "sse4.2", "avx", "avx2", "avx512"}),
          K::choice("packet", static_cast<EmbreePacket P::*>(&P::packet),
                    {{"auto", EmbreePacket::Auto},
                     {"4", EmbreePacket::Lanes4},
                     {"8", EmbreePacket::Lanes8},
                     {"16", EmbreePacket::Lanes16}},
                    "Rays per packet query (rtcIntersect4/8/16); `auto` = Embree's native width at "
                    "its instruction set.")
              .crossed()};
}

/// The spelling of an `isa` value.
const char* isa_spelling(EmbreeIsa isa) {
  switch (isa) {
    case EmbreeIsa::Build: return "build";
    case EmbreeIsa::Cpu: return "cpu";
    default: return isa_name(resolve_embree_isa(isa, 0));
  }
}

}  // namespace

const knobs::KnobTable<EmbreeParams>& EmbreeParams::knobs() {
  static const knobs::KnobTable<EmbreeParams> table("embree", embree_knobs<EmbreeParams>());
  return table;
}

const knobs::KnobTable<EmbreePointsParams>& EmbreePointsParams::knobs() {
  static const knobs::KnobTable<EmbreePointsParams> table("embree_points", embree_knobs<EmbreePointsParams>());
  return table;
}

const knobs::KnobTable<EmbreeTrianglesParams>& EmbreeTrianglesParams::knobs() {
  static const knobs::KnobTable<EmbreeTrianglesParams> table("embree_triangles",
                                                             embree_knobs<EmbreeTrianglesParams>());
  return table;
}

Isa resolve_embree_isa(EmbreeIsa isa, IsaSet cpu) {
  switch (isa) {
    case EmbreeIsa::Build: return build_isa();
    case EmbreeIsa::Cpu: {
      Isa best = Isa::Sse2;
      for (Isa level : isas_in(cpu)) best = level;
      return best;
    }
    case EmbreeIsa::Sse2: return Isa::Sse2;
    case EmbreeIsa::Sse42: return Isa::Sse42;
    case EmbreeIsa::Avx: return Isa::Avx;
    case EmbreeIsa::Avx2: return Isa::Avx2;
    case EmbreeIsa::Avx512: return Isa::Avx512;
  }
  return Isa::Sse2;
}

int resolve_embree_packet(EmbreePacket packet, Isa isa) {
  switch (packet) {
    case EmbreePacket::Auto: return isa_lanes(isa);
    case EmbreePacket::Lanes4: return 4;
    case EmbreePacket::Lanes8: return 8;
    case EmbreePacket::Lanes16: return 16;
  }
  return 16;
}

void check_embree_isa(EmbreeIsa isa, IsaSet cpu, const char* owner) {
  const Isa level = resolve_embree_isa(isa, cpu);
  if (cpu & isa_bit(level)) return;
  throw knobs::ConfigError(std::string(owner) + ": knob 'isa' = " + isa_spelling(isa) + " needs " +
                    isa_features(level) + ", which this CPU lacks (it has " + isa_list(cpu) + ")");
}

}  // namespace accel
