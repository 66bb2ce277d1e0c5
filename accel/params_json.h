#pragma once
// The older knob reader, still used by photon/'s parameter structs: every key must be known and
// of the right type, and every value in range, or a one-line ConfigError names the owner and
// the key. New parameter structs use a knob table (knob_table.h), which also writes JSON, reads
// --knob and generates the docs from one list; the structures' params all moved there.

#include "config_error.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <initializer_list>
#include <optional>
#include <utility>
#include <vector>

namespace accel {

/// Reads knobs one key at a time from a JSON object (or null: all defaults), then finish()
/// rejects any key nobody asked for. Absent keys leave the default in place.
class KnobReader {
 public:
  KnobReader(std::string_view structure, const nlohmann::json& j) : structure_(structure), j_(j) {
    if (!j_.is_null() && !j_.is_object())
      fail("parameters must be a JSON object, got " + std::string(j_.type_name()));
  }

  /// An integer knob in [lo, hi].
  void read(const char* key, int& value, int lo, int hi) {
    const nlohmann::json* v = find(key);
    if (!v) return;
    if (!v->is_number_integer()) fail_type(key, "an integer", *v);
    const auto x = v->get<std::int64_t>();
    if (x < lo || x > hi) fail_range(key, std::to_string(x), std::to_string(lo), std::to_string(hi));
    value = int(x);
  }

  /// A number knob in [lo, hi] (integers accepted).
  void read(const char* key, float& value, float lo, float hi) {
    const nlohmann::json* v = find(key);
    if (!v) return;
    if (!v->is_number()) fail_type(key, "a number", *v);
    const double x = v->get<double>();
    if (!(x >= lo && x <= hi))
      fail_range(key, v->dump(), nlohmann::json(lo).dump(), nlohmann::json(hi).dump());
    value = float(x);
  }

  /// A 64-bit knob such as a seed: any integer >= 0.
  void read(const char* key, std::uint64_t& value) {
    const nlohmann::json* v = find(key);
    if (!v) return;
    if (!v->is_number_unsigned() && !(v->is_number_integer() && v->get<std::int64_t>() >= 0))
      fail("parameter '" + std::string(key) + "' must be an integer >= 0, got " + v->dump());
    value = v->get<std::uint64_t>();
  }

  /// A 64-bit count in [lo, hi].
  void read(const char* key, std::uint64_t& value, std::uint64_t lo, std::uint64_t hi) {
    std::uint64_t x = value;
    read(key, x);
    if (x < lo || x > hi) fail_range(key, std::to_string(x), std::to_string(lo), std::to_string(hi));
    value = x;
  }

  /// A length in world units > 0, or "auto" (an empty optional: the owner picks it).
  void read_auto_or_positive(const char* key, std::optional<float>& value) {
    const nlohmann::json* v = find(key);
    if (!v) return;
    if (v->is_string() && v->get<std::string>() == "auto") {
      value.reset();
    } else if (v->is_number() && v->get<double>() > 0.0 && v->get<double>() <= 3.0e38) {
      value = float(v->get<double>());
    } else {
      fail("parameter '" + std::string(key) + "' must be a number > 0 (world units) or \"auto\", got " +
           v->dump());
    }
  }

  /// A boolean knob.
  void read(const char* key, bool& value) {
    const nlohmann::json* v = find(key);
    if (!v) return;
    if (!v->is_boolean()) fail_type(key, "true or false", *v);
    value = v->get<bool>();
  }

  /// An enum knob spelled as one of `names` (pairs of spelling and value).
  template <class E>
  void read_enum(const char* key, E& value, std::initializer_list<std::pair<const char*, E>> names) {
    const nlohmann::json* v = find(key);
    if (!v) return;
    std::string valid;
    for (const auto& [name, e] : names) {
      if (!valid.empty()) valid += '|';
      valid += name;
    }
    if (!v->is_string()) fail_type(key, "one of " + valid, *v);
    const std::string s = v->get<std::string>();
    for (const auto& [name, e] : names)
      if (s == name) {
        value = e;
        return;
      }
    fail("parameter '" + std::string(key) + "' must be one of " + valid + ", got '" + s + "'");
  }

  /// The raw value of a knob the owner checks itself (nullptr when absent); marks it known.
  const nlohmann::json* take(const char* key) { return find(key); }

  /// Throws for the first key that no read() asked for.
  void finish() const {
    if (!j_.is_object()) return;
    for (auto it = j_.begin(); it != j_.end(); ++it) {
      bool known = false;
      for (const std::string& k : seen_) known = known || k == it.key();
      if (!known) fail("unknown parameter '" + it.key() + "'");
    }
  }

 private:
  const nlohmann::json* find(const char* key) {
    seen_.emplace_back(key);
    if (!j_.is_object()) return nullptr;
    const auto it = j_.find(key);
    return it == j_.end() ? nullptr : &*it;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw ConfigError(structure_ + ": " + what);
  }
  [[noreturn]] void fail_type(const char* key, const std::string& want, const nlohmann::json& v) const {
    fail("parameter '" + std::string(key) + "' must be " + want + ", got " + v.dump());
  }
  [[noreturn]] void fail_range(const char* key, const std::string& got, const std::string& lo,
                               const std::string& hi) const {
    fail("parameter '" + std::string(key) + "' must be in [" + lo + ", " + hi + "], got " + got);
  }

  std::string structure_;
  const nlohmann::json& j_;
  std::vector<std::string> seen_;
};

}  // namespace accel
