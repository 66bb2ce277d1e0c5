#include "message.h"

#include <charconv>
#include <cstdio>

namespace input {
namespace {

/// Appends to `out` until it holds more than `limit` characters; returns false once it does.
class Writer {
 public:
  explicit Writer(std::size_t limit) : limit_(limit) {}
  bool put(std::string_view s) {
    out_.append(s.substr(0, limit_ + 1 - std::min(out_.size(), limit_ + 1)));
    return out_.size() <= limit_;
  }
  bool full() const { return out_.size() > limit_; }
  std::string& text() { return out_; }

 private:
  std::size_t limit_;
  std::string out_;
};

std::string quoted(const std::string& s) {
  // nlohmann's escaping of one string is bounded by the string; cut long strings first.
  const nlohmann::json j = s.size() > 256 ? s.substr(0, 256) : s;
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

bool write(const nlohmann::json& v, Writer& w, int depth) {
  if (w.full()) return false;
  if (depth > 8) return w.put("...");
  switch (v.type()) {
    case nlohmann::json::value_t::array: {
      if (!w.put("[")) return false;
      bool first = true;
      for (const auto& e : v) {
        if (!first && !w.put(",")) return false;
        first = false;
        if (!write(e, w, depth + 1)) return false;
      }
      return w.put("]");
    }
    case nlohmann::json::value_t::object: {
      if (!w.put("{")) return false;
      bool first = true;
      for (const auto& [key, e] : v.items()) {
        if (!first && !w.put(",")) return false;
        first = false;
        if (!w.put(quoted(key)) || !w.put(":") || !write(e, w, depth + 1)) return false;
      }
      return w.put("}");
    }
    case nlohmann::json::value_t::string:
      return w.put(quoted(v.get_ref<const std::string&>()));
    default:  // numbers, booleans, null: short
      return w.put(v.dump());
  }
}

std::size_t utf8_boundary(std::string_view s, std::size_t at) {
  while (at > 0 && at < s.size() && (static_cast<unsigned char>(s[at]) & 0xC0) == 0x80) --at;
  return at;
}

}  // namespace

std::string one_line(std::string_view s, std::size_t max_chars) {
  std::string out;
  const bool cut = s.size() > max_chars;
  const std::size_t keep = cut ? utf8_boundary(s, max_chars > 3 ? max_chars - 3 : 0) : s.size();
  out.reserve(keep + 3);
  for (char c : s.substr(0, keep)) out += (static_cast<unsigned char>(c) < 32 || c == 127) ? ' ' : c;
  if (cut) out += "...";
  return out;
}

std::string brief(const nlohmann::json& value, std::size_t max_chars) {
  Writer w(max_chars);
  write(value, w, 0);
  std::string& s = w.text();
  if (s.size() > max_chars) s = s.substr(0, utf8_boundary(s, max_chars > 3 ? max_chars - 3 : 0)) + "...";
  return s;
}

std::string pointer_token(std::string_view key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

}  // namespace input
