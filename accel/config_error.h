#pragma once
// The error every configuration check in accel/ throws (structure names, knobs, build limits).

#include <stdexcept>

namespace accel {

/// A bad structure name, knob or resource limit; what() is one line naming the knob.
struct ConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace accel
