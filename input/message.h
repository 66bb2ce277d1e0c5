#pragma once
// Error messages that stay short and on one line, whatever the input put in them.

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <string_view>

namespace input {

/// Longest error line, characters; longer messages are cut with "..." (docs: "about 200").
inline constexpr std::size_t kMaxMessageChars = 200;

/// `s` on one line (control characters become spaces) and at most `max_chars` characters
/// (bytes), cut at a UTF-8 character boundary and ending in "..." when cut.
std::string one_line(std::string_view s, std::size_t max_chars = kMaxMessageChars);

/// A JSON value as the user wrote it, for a message: at most `max_chars` characters, ending in
/// "..." when cut. Serializes only what it shows, so a huge or deep value costs no more than that.
std::string brief(const nlohmann::json& value, std::size_t max_chars = 48);

/// A key as one JSON pointer token (RFC 6901: "~" -> "~0", "/" -> "~1").
std::string pointer_token(std::string_view key);

}  // namespace input
