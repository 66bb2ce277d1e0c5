#pragma once
// JSON text to a document, strictly: a nesting limit enforced while parsing (so no later
// recursion over the document can run out of stack), duplicate keys rejected, and every error
// one line naming the JSON pointer and the line and column where it was found.

#include "error.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string_view>

namespace input {

/// Deepest nesting of arrays and objects accepted (every accelbench format needs fewer than 10).
inline constexpr std::size_t kMaxJsonDepth = 64;

/// Parses `text` as one JSON value. Throws InputError whose what() is
/// "<JSON pointer>: <what is wrong>", e.g.
///   "/spheres/0/radius: invalid JSON: parse error at line 1, column 48: syntax error ..."
///   "/camera: duplicate key \"camera\" at line 9, column 11"
///   "/0/0/0/0/...: nested deeper than 64 levels at line 1, column 65"
///   "/spheres/1/radius: must be a finite number, got NaN"  (NaN and Infinity literals)
/// The pointer is "(root)" for the whole document.
nlohmann::json parse_json(std::string_view text, std::size_t max_depth = kMaxJsonDepth);

/// A JSON pointer for messages: "(root)" when empty, and cut to stay short.
std::string display_pointer(std::string_view pointer);

}  // namespace input
