#include "embree_native.h"

#include <stdexcept>
#include <string>

namespace accel {

void EmbreeNative::check_count(std::size_t count, const char* owner, const char* what) const {
  if (count != embree_.stats().primitives)
    throw std::invalid_argument(std::string(owner) + ": " + std::to_string(count) + " " + what +
                                " attached to a structure over " + std::to_string(embree_.stats().primitives) +
                                " primitives");
}

void EmbreeNative::make_native(embree_detail::Scene scene, std::chrono::steady_clock::time_point start) {
  embree_.commit(scene);  // throws on the budget (a refused buffer included) and Embree's errors
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  embree_.replace_scene(std::move(scene));
  native_ = true;
  embree_.mutable_stats().build_ms = ms;
}

}  // namespace accel
