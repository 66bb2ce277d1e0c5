#pragma once
// The one error type of the input layer.

#include <stdexcept>

namespace input {

/// Input that cannot be read or parsed; what() is one line that starts with where the problem is
/// (a file name, a JSON pointer, a line) and says what is wrong.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace input
