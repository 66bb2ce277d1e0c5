#pragma once
// The structure registry: the one list of structures. The names, the std::variant every render
// loop is compiled from, make_accel, the knob reference, the benchmarks and the sweeps' knob
// discovery all derive from `Registry` below. A new structure is its own files and one line
// here.

#include "auto_select.h"
#include "bvh.h"
#include "embree_accel.h"
#include "embree_points.h"
#include "embree_triangles.h"
#include "kdtree.h"
#include "naive.h"
#include "octree.h"
#include "traversal.h"
#include "wide_bvh/wide_bvh.h"

#include <type_traits>
#include <variant>

namespace accel {

template <class... T>
struct TypeList {};

/// Every registered entry, in display order: the structures, a structure compiled out of this
/// build (it has kMissing), and selectors (kSelector) that pick one of the structures.
using Registry = TypeList<Naive, Octree, KdTree, Bvh, Bvh4, Bvh8, EmbreeAccel, EmbreePoints, EmbreeTriangles,
                         AutoSelect>;

/// An entry that chooses among the structures instead of being one (`auto`).
template <class E>
concept SelectorEntry = requires { E::kSelector; };
/// An entry compiled out of this build; E::kMissing says why.
template <class E>
concept MissingEntry = requires { E::kMissing; };
/// An entry that is a structure built in this build (an alternative of the variant).
template <class E>
concept StructureEntry = !SelectorEntry<E> && !MissingEntry<E>;

namespace registry_detail {
template <class List, class Out>
struct StructuresOf;
template <class Out>
struct StructuresOf<TypeList<>, Out> {
  using type = Out;
};
template <class E, class... Rest, class... Out>
struct StructuresOf<TypeList<E, Rest...>, std::variant<Out...>> {
  using type = typename StructuresOf<
      TypeList<Rest...>, std::conditional_t<StructureEntry<E>, std::variant<Out..., E>, std::variant<Out...>>>::type;
};
template <class S>
constexpr bool meets_contract() {
  static_assert(TraversalStructure<S>, "a registered structure does not meet the traversal contract (traversal.h)");
  return true;
}
template <class... S>
constexpr bool all_meet_contract(std::variant<S...>*) {
  return (meets_contract<S>() && ...);
}
}  // namespace registry_detail

/// One alternative per structure built here; visited once per render.
using StructureVariant = typename registry_detail::StructuresOf<Registry, std::variant<>>::type;

static_assert(registry_detail::all_meet_contract(static_cast<StructureVariant*>(nullptr)),
              "every registered structure meets the traversal contract (traversal.h)");

/// Calls f.template operator()<E>() for every registry entry E, in order.
template <class F>
void for_each_entry(F&& f) {
  [&]<class... E>(TypeList<E...>) { (f.template operator()<E>(), ...); }(Registry{});
}

}  // namespace accel
