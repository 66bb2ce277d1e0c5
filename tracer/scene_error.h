#pragma once
// The one error type of scene loading and validation.

#include <stdexcept>

namespace tracer {

/// A scene that cannot be loaded: what() is one line naming where (a JSON pointer such as
/// `/spheres/12/radius`, or `file:line` for text formats) and what is wrong.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace tracer
