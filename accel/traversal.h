#pragma once
// The traversal contract, as a concept every registered structure is checked against.
//
// A structure is built from the primitives' bounding boxes (primitive id = index) and one
// parameter struct with a knob table. It answers
//   intersect<Count>(ray, leaf_fn, counters)  closest hit: calls leaf_fn(prim_id, ray) on the
//       primitives the ray may hit; leaf_fn tests one primitive with the caller's routine and
//       may shorten ray.tmax (returning true when it did); the structure must visit every
//       primitive that could hit within the current (shrinking) interval, ties included;
//   occluded<Count>(ray, leaf_fn, counters)  any hit: true as soon as a leaf_fn call returns
//       true; the ray is not changed.
// With Count the structure adds to *counters (rays, nodes visited, boxes tested, primitives
// tested); without it, counters is not touched and the timed path carries no branch for it.

#include "build_limits.h"
#include "geometry.h"
#include "knobs/knob_table.h"
#include "stats.h"

#include <concepts>
#include <cstdint>
#include <span>

namespace accel {

/// A leaf function of the contract, for checking structures against it (never called).
struct LeafFnArchetype {
  bool operator()(std::uint32_t prim_id, Ray& ray) const;
};

/// What every structure in the registry provides: a name and summary, a parameter struct with a
/// knob table, a constructor from boxes, knobs and limits, statistics, and both queries in the
/// timed and the counting instantiation.
template <class S>
concept TraversalStructure =
    std::movable<S> && std::default_initializable<S> &&
    std::constructible_from<S, std::span<const Aabb>, const typename S::Params&, const BuildLimits&> &&
    requires(const S& s, Ray& ray, const Ray& const_ray, LeafFnArchetype& leaf, TraversalCounters* c) {
      { S::kName } -> std::convertible_to<const char*>;
      { S::kSummary } -> std::convertible_to<const char*>;
      { S::Params::knobs() } -> std::same_as<const knobs::KnobTable<typename S::Params>&>;
      { s.params() } -> std::same_as<const typename S::Params&>;
      { s.stats() } -> std::same_as<const BuildStats&>;
      { s.template intersect<false>(ray, leaf, c) } -> std::same_as<void>;
      { s.template intersect<true>(ray, leaf, c) } -> std::same_as<void>;
      { s.template occluded<false>(const_ray, leaf, c) } -> std::same_as<bool>;
      { s.template occluded<true>(const_ray, leaf, c) } -> std::same_as<bool>;
    };

}  // namespace accel
