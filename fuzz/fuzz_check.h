#pragma once
// What every fuzz target checks besides "no crash, no hang, no leak": a refusal is one short
// line, and what a reader accepts, the program can write back and read again. A broken property
// aborts, which libFuzzer reports as a crash with the input that caused it.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

namespace fuzz {

/// Longest message a reader may raise before the command line cuts it (input::one_line).
inline constexpr std::size_t kMaxMessage = 1000;

/// Aborts with `what` (and the offending text, shortened) when `ok` is false.
inline void require(bool ok, const char* what, std::string_view detail = {}) {
  if (ok) return;
  const std::string shown(detail.substr(0, 300));
  std::fprintf(stderr, "fuzz property broken: %s: %s\n", what, shown.c_str());
  std::abort();
}

/// An error message must be one line, not too long, and start with `prefix` (its file name).
inline void check_message(std::string_view message, std::string_view prefix) {
  require(message.find('\n') == std::string_view::npos, "a message spans lines", message);
  require(message.size() <= kMaxMessage, "a message is too long", message.substr(0, 200));
  require(message.substr(0, prefix.size()) == prefix, "a message does not start with its file", message);
}

/// The fuzzer's bytes as text.
inline std::string_view text_of(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

}  // namespace fuzz
