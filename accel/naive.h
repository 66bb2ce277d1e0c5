#pragma once
// The plain loop over every primitive: the baseline every speedup is measured against.

#include "build_limits.h"
#include "geometry.h"
#include "knobs/knob_table.h"
#include "stats.h"

#include <cstdint>
#include <span>

namespace accel {

/// The naive structure has no knobs.
struct NaiveParams {
  /// The empty table: any knob is an error.
  static const knobs::KnobTable<NaiveParams>& knobs() {
    static const knobs::KnobTable<NaiveParams> table("naive", {});
    return table;
  }
};

class Naive {
 public:
  using Params = NaiveParams;
  static constexpr const char* kName = "naive";
  static constexpr const char* kSummary = "the loop over every primitive: the baseline";

  Naive() = default;
  Naive(std::span<const Aabb> boxes, const NaiveParams& params, const BuildLimits&) : Naive(boxes, params) {}
  explicit Naive(std::span<const Aabb> boxes, const NaiveParams& = {})
      : count_(static_cast<std::uint32_t>(boxes.size())) {
    stats_.primitives = count_;
    stats_.prim_refs = count_;
    stats_.nodes = 0;
    stats_.leaves = 0;
    stats_.sah_cost = double(count_);
  }

  /// Closest hit: calls leaf_fn(prim_id, ray) for every primitive; leaf_fn shortens ray.tmax.
  template <bool Count = false, class LeafFn>
  void intersect(Ray& ray, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    if constexpr (Count) {
      counters->rays++;
      counters->prims_tested += count_;
    }
    for (std::uint32_t i = 0; i < count_; ++i) leaf_fn(i, ray);
  }

  /// Any hit: stops at the first primitive whose leaf_fn returns true.
  template <bool Count = false, class LeafFn>
  bool occluded(const Ray& ray_in, LeafFn&& leaf_fn, TraversalCounters* counters = nullptr) const {
    Ray ray = ray_in;
    if constexpr (Count) counters->rays++;
    for (std::uint32_t i = 0; i < count_; ++i) {
      if constexpr (Count) counters->prims_tested++;
      if (leaf_fn(i, ray)) return true;
    }
    return false;
  }

  const NaiveParams& params() const { return params_; }
  const BuildStats& stats() const { return stats_; }

 private:
  NaiveParams params_;
  std::uint32_t count_ = 0;
  BuildStats stats_;
};

}  // namespace accel
