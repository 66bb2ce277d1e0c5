#include "json_read.h"

#include "message.h"

#include <algorithm>
#include <cctype>
#include <iterator>
#include <string>
#include <vector>

namespace input {
namespace {

using nlohmann::json;

/// A char iterator that publishes how far the parser has read, so that the SAX handler can say
/// where an event happened (nlohmann's SAX events carry no position).
class TrackingIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  TrackingIterator() = default;
  TrackingIterator(const char* p, const char** furthest) : p_(p), furthest_(furthest) {}
  reference operator*() const {
    if (p_ > *furthest_) *furthest_ = p_;
    return *p_;
  }
  TrackingIterator& operator++() {
    ++p_;
    return *this;
  }
  TrackingIterator operator++(int) {
    TrackingIterator t = *this;
    ++p_;
    return t;
  }
  bool operator==(const TrackingIterator& o) const { return p_ == o.p_; }
  bool operator!=(const TrackingIterator& o) const { return p_ != o.p_; }

 private:
  const char* p_ = nullptr;
  const char** furthest_ = nullptr;
};

/// "line L, column C" of byte offset `at` (1-based, columns in bytes).
std::string line_column(std::string_view text, std::size_t at) {
  at = std::min(at, text.size());
  std::size_t line = 1, line_start = 0;
  for (std::size_t i = 0; i < at; ++i)
    if (text[i] == '\n') ++line, line_start = i + 1;
  return "line " + std::to_string(line) + ", column " + std::to_string(at - line_start + 1);
}

/// Builds the document like nlohmann's DOM parser, and also tracks the JSON pointer of the value
/// being parsed, refuses nesting past the limit and refuses a key its object already has.
class Builder : public nlohmann::json_sax<json> {
 public:
  Builder(std::string_view text, std::size_t max_depth, const char** furthest)
      : text_(text), max_depth_(max_depth), furthest_(furthest) {}

  bool null() override { return value(json(nullptr)); }
  bool boolean(bool b) override { return value(json(b)); }
  bool number_integer(number_integer_t v) override { return value(json(v)); }
  bool number_unsigned(number_unsigned_t v) override { return value(json(v)); }
  bool number_float(number_float_t v, const string_t&) override { return value(json(v)); }
  bool string(string_t& s) override { return value(json(std::move(s))); }
  bool binary(binary_t& b) override { return value(json::binary(std::move(b))); }

  bool start_object(std::size_t) override { return open(json::object()); }
  bool start_array(std::size_t) override { return open(json::array()); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }

  bool key(string_t& k) override {
    json& object = *frames_.back().value;
    frames_.back().key = k;
    if (object.contains(k)) {
      error_ = display_pointer(pointer(true)) + ": duplicate key at " + where() +
               " (each key may appear only once in an object)";
      return false;
    }
    pending_ = &object[k];
    return true;
  }

  bool parse_error(std::size_t position, const std::string& last_token,
                   const nlohmann::detail::exception& ex) override {
    if (ex.id == 406) {  // a number past double's range: valid syntax, an impossible value
      const std::size_t end = std::size_t(*furthest_ - text_.data());
      error_ = display_pointer(pointer(false)) + ": number " + brief(json(last_token), 40) +
               " is beyond double range (magnitude at most 1.8e308) at " +
               line_column(text_, end >= last_token.size() ? end - last_token.size() : 0);
      return false;
    }
    std::string msg = ex.what();
    if (const std::size_t pos = msg.find("] "); msg.rfind("[json.exception", 0) == 0 && pos != std::string::npos)
      msg = msg.substr(pos + 2);
    // A NaN or Infinity literal (as some writers emit) is a value error, not a typo.
    const auto in_word = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '-'; };
    std::size_t start = std::min(position, text_.size());
    while (start > 0 && in_word(text_[start - 1])) --start;
    std::size_t end = start;
    while (end < text_.size() && in_word(text_[end])) ++end;
    const std::string_view word = text_.substr(start, end - start);
    for (std::string_view literal : {"NaN", "nan", "-NaN", "-nan", "Infinity", "-Infinity", "inf", "-inf"})
      if (word == literal) {
        error_ = display_pointer(pointer(false)) + ": must be a finite number, got " + std::string(word);
        return false;
      }
    // nlohmann quotes the whole token it was reading ("last read: '...'"): as long as the input's
    // longest string, and as raw as its bytes.
    error_ = display_pointer(pointer(false)) + ": invalid JSON: " + one_line(msg, 160);
    return false;
  }

  json result() { return std::move(root_); }
  const std::string& error() const { return error_; }

 private:
  struct Frame {
    json* value;      ///< The array or object being filled.
    std::string key;  ///< Objects: the last key read.
  };

  /// Where the current value goes: the root, the end of an array, or the pending key.
  json* place(json&& v) {
    if (frames_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    json& parent = *frames_.back().value;
    if (parent.is_array()) {
      parent.push_back(std::move(v));
      return &parent.back();
    }
    *pending_ = std::move(v);
    return pending_;
  }
  bool value(json&& v) {
    place(std::move(v));
    return true;
  }
  bool open(json&& container) {
    if (frames_.size() >= max_depth_) {
      error_ = display_pointer(pointer(false)) + ": nested deeper than " + std::to_string(max_depth_) +
               " levels at " + where();
      return false;
    }
    frames_.push_back({place(std::move(container)), {}});
    return true;
  }
  bool close() {
    frames_.pop_back();
    return true;
  }

  /// The pointer of the value being parsed. In an array that is the element after the last one
  /// read; `at_key` names the key just read in the innermost object.
  std::string pointer(bool at_key) const {
    std::string p;
    for (std::size_t i = 0; i < frames_.size(); ++i) {
      const Frame& f = frames_[i];
      const bool innermost = i + 1 == frames_.size();
      if (f.value->is_array()) {
        const std::size_t n = f.value->size();
        p += '/';
        p += std::to_string(innermost ? n : n - 1);
      } else {
        if (f.key.empty() && innermost && !at_key) break;
        p += '/';
        p += pointer_token(f.key);
      }
    }
    return p;
  }
  /// Where the parser is: the last character it read.
  std::string where() const { return line_column(text_, std::size_t(*furthest_ - text_.data())); }

  std::string_view text_;
  std::size_t max_depth_;
  const char** furthest_;
  json root_;
  std::vector<Frame> frames_;
  json* pending_ = nullptr;
  std::string error_;
};

}  // namespace

std::string display_pointer(std::string_view pointer) {
  if (pointer.empty()) return "(root)";
  return one_line(pointer, 80);  // keys may hold newlines and any length (fuzzing found both)
}

json parse_json(std::string_view text, std::size_t max_depth) {
  const char* furthest = text.data();
  Builder builder(text, max_depth, &furthest);
  const TrackingIterator first(text.data(), &furthest), last(text.data() + text.size(), &furthest);
  if (!json::sax_parse(first, last, &builder, nlohmann::detail::input_format_t::json, /*strict=*/true)) {
    throw InputError(builder.error().empty() ? "(root): invalid JSON" : builder.error());
  }
  return builder.result();
}

}  // namespace input
