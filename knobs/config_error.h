#pragma once
// The error every configuration check throws (structure names, knobs, build limits, integrator
// knobs): what() is one line naming what is wrong.

#include <stdexcept>

namespace knobs {

/// A bad structure name, knob or resource limit; what() is one line naming the knob.
struct ConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace knobs
