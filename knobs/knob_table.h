#pragma once
// Knob tables: one table per parameter struct lists every knob once (name, member, range, unit,
// doc line); the defaults are read from the struct itself, so they are written once, in the
// struct. The table drives JSON in and out, validation with one-line messages, the generic
// `--knob name=value` command-line flag, and the generated knob reference in the docs.
//
// This is the one knob system of accelbench: the structures' params, the integrators' (whitted,
// spd, photon, ppm), the photon trees' and the gather's all have a table, and nothing else reads
// or writes a knob. A table also says which knobs get a shorthand flag on the command line
// (shorthand()) and which trade accuracy for time in `accelbench fronts` (front()). It depends on
// nlohmann-json only, so every library can use it.
//
//   struct MyParams {
//     int depth = 5;  ///< ...
//     static const knobs::KnobTable<MyParams>& knobs() {
//       static const knobs::KnobTable<MyParams> t("mine", {
//           knobs::Knob<MyParams>::integer("depth", &MyParams::depth, 0, 64, "levels", "What it does.")});
//       return t;
//     }
//   };
//   MyParams p = MyParams::knobs().from_json(j);   // throws ConfigError, one line
//   nlohmann::json out = MyParams::knobs().to_json(p);   // or nlohmann::json(p)

#include "knobs/config_error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <concepts>
#include <cstdlib>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace knobs {

/// The name of every table's random-seed knob. The harness renders a knob set again with
/// independent noise by setting it (fronts' seeds, the halves of a stochastic reference); a
/// table without it has no noise to vary.
inline constexpr const char* kSeedKnob = "seed";

/// The kind of value a knob holds.
enum class KnobType : std::uint8_t {
  Integer,  ///< A whole number in [min, max].
  Number,   ///< A real number in [min, max]; integers are accepted.
  Boolean,  ///< true or false.
  Choice,   ///< One of a list of spellings (an enum class in the struct).
};

/// How `accelbench fronts` studies a knob that trades accuracy for time (docs/accuracy.md).
struct Front {
  /// The values a front tries by default, cheapest first (a JSON array).
  const char* values = "[]";
  /// The integrator of the reference render; "" = the knob's own. A consistent estimator
  /// (progressive photon mapping) makes the reference for a biased one's knobs, at that
  /// integrator's own reference knobs.
  std::string_view reference_integrator;
  /// The reference's knobs for the knob's own integrator (a JSON object): set so that this
  /// knob's error is negligible. "" with another reference integrator.
  const char* reference = "";
  /// Knobs of a second, weaker reference (a JSON object, "" for none) whose difference from the
  /// reference estimates the reference's own truncation error (deterministic references).
  const char* check = "";
  /// The reference is stochastic: rendered twice with independent seeds, its noise estimated
  /// from the two halves.
  bool stochastic = false;
};

/// One knob of the parameter struct P.
template <class P>
class Knob {
 public:
  /// An integer member in [lo, hi] (hi up to 2^64 - 1, for seeds).
  template <std::integral T>
    requires(!std::same_as<T, bool>)
  static Knob integer(const char* name, T P::*member, long long lo, unsigned long long hi,
                      const char* unit, const char* doc) {
    Knob k(name, KnobType::Integer, unit, doc);
    k.lo_ = double(lo);
    k.hi_ = double(hi);
    k.ilo_ = lo;
    k.ihi_ = hi;
    k.get_ = [member](const P& p) { return nlohmann::json(p.*member); };
    k.set_ = [member](P& p, const nlohmann::json& v) {
      p.*member = v.is_number_unsigned() ? T(v.get<std::uint64_t>()) : T(v.get<long long>());
    };
    k.valid_ = [member, lo, hi](const P& p) {
      const T x = p.*member;
      if constexpr (std::is_signed_v<T>)
        if (x < 0) return static_cast<long long>(x) >= lo;
      const auto u = static_cast<unsigned long long>(x);
      return (lo <= 0 || u >= static_cast<unsigned long long>(lo)) && u <= hi;
    };
    return k;
  }

  /// A floating-point member in [lo, hi].
  template <std::floating_point T>
  static Knob number(const char* name, T P::*member, double lo, double hi, const char* unit,
                     const char* doc) {
    Knob k(name, KnobType::Number, unit, doc);
    k.lo_ = lo;
    k.hi_ = hi;
    k.get_ = [member](const P& p) { return nlohmann::json(shortest_double(p.*member)); };
    k.set_ = [member](P& p, const nlohmann::json& v) { p.*member = T(v.get<double>()); };
    k.number_member_ = [member](const P& p) { return std::optional<double>(double(p.*member)); };
    return k;
  }

  /// An optional floating-point member in [lo, hi], or the word "auto" (empty: the owner picks
  /// the value).
  template <std::floating_point T>
  static Knob number_or_auto(const char* name, std::optional<T> P::*member, double lo, double hi,
                             const char* unit, const char* doc) {
    Knob k(name, KnobType::Number, unit, doc);
    k.lo_ = lo;
    k.hi_ = hi;
    k.word_ = "auto";
    k.get_ = [member](const P& p) {
      return (p.*member) ? nlohmann::json(shortest_double(*(p.*member))) : nlohmann::json("auto");
    };
    k.set_ = [member](P& p, const nlohmann::json& v) {
      if (v.is_string()) p.*member = std::nullopt;
      else p.*member = T(v.get<double>());
    };
    k.number_member_ = [member](const P& p) {
      return (p.*member) ? std::optional<double>(double(*(p.*member))) : std::nullopt;
    };
    return k;
  }

  /// A floating-point member in [lo, largest finite], or the word "inf" for +infinity.
  template <std::floating_point T>
  static Knob number_or_infinity(const char* name, T P::*member, double lo, const char* unit,
                                 const char* doc) {
    Knob k(name, KnobType::Number, unit, doc);
    k.lo_ = lo;
    k.hi_ = std::numeric_limits<double>::infinity();
    k.word_ = "inf";
    k.get_ = [member](const P& p) {
      return std::isinf(p.*member) ? nlohmann::json("inf") : nlohmann::json(shortest_double(p.*member));
    };
    k.set_ = [member](P& p, const nlohmann::json& v) {
      p.*member = v.is_string() ? std::numeric_limits<T>::infinity() : T(v.get<double>());
    };
    k.number_member_ = [member](const P& p) {
      return p.*member == std::numeric_limits<T>::infinity() ? std::nullopt
                                                              : std::optional<double>(double(p.*member));
    };
    return k;
  }

  /// A boolean member.
  static Knob boolean(const char* name, bool P::*member, const char* doc) {
    Knob k(name, KnobType::Boolean, "", doc);
    k.get_ = [member](const P& p) { return nlohmann::json(p.*member); };
    k.set_ = [member](P& p, const nlohmann::json& v) { p.*member = v.get<bool>(); };
    return k;
  }

  /// An enum member, spelled as one of `names` (spelling, value), in display order.
  template <class E>
  static Knob choice(const char* name, E P::*member, std::vector<std::pair<std::string, E>> names,
                     const char* doc) {
    Knob k(name, KnobType::Choice, "", doc);
    for (const auto& [spelling, e] : names) k.choices_.push_back(spelling);
    k.get_ = [member, names](const P& p) {
      for (const auto& [spelling, e] : names)
        if (p.*member == e) return nlohmann::json(spelling);
      return nlohmann::json(nullptr);  // a value outside the table; from_json rejects it
    };
    k.set_ = [member, names](P& p, const nlohmann::json& v) {
      for (const auto& [spelling, e] : names)
        if (choice_spelling(v) == spelling) p.*member = e;
    };
    k.valid_ = [member, names](const P& p) {
      for (const auto& [spelling, e] : names)
        if (p.*member == e) return true;
      return false;
    };
    return k;
  }

  /// Marks a knob that changes the algorithm rather than tuning it (a split rule, a placement):
  /// benchmarks and plots show each of its values as a variant of its own.
  Knob& variant() {
    variant_ = true;
    return *this;
  }
  /// Marks a knob that shapes the tree jointly with the other crossed knobs (depth and leaf
  /// size): tests cross their probe values instead of varying them one at a time.
  Knob& crossed() {
    crossed_ = true;
    return *this;
  }
  /// The values tests try for this knob. Without this: every choice and both booleans; the
  /// range ends and the default for numbers.
  Knob& probes(std::vector<nlohmann::json> values) {
    probes_ = std::move(values);
    return *this;
  }

  /// Makes the lower end of a number's range open: (lo, hi].
  Knob& open_below() {
    open_below_ = true;
    return *this;
  }
  /// Gives the knob a flag of its own on the commands that take knobs (`max_depth` as
  /// `--max-depth`, or the spelling given), beside the generic `--knob max_depth=...`.
  Knob& shorthand(const char* flag = nullptr) {
    shorthand_ = true;
    if (flag) flag_ = flag;
    return *this;
  }
  /// Marks a knob that trades accuracy for time, and how `accelbench fronts` studies it.
  Knob& front(Front f) {
    front_ = f;
    return *this;
  }

  const std::string& name() const { return name_; }  ///< Spelling in JSON and on --knob.
  KnobType type() const { return type_; }             ///< Kind of value.
  const std::string& unit() const { return unit_; }   ///< Unit of the value ("" when none).
  const std::string& doc() const { return doc_; }     ///< One line: what the knob does.
  double min() const { return lo_; }                  ///< Smallest accepted number.
  double max() const { return hi_; }                  ///< Largest accepted number.
  /// Spellings of a Choice knob, in display order.
  const std::vector<std::string>& choices() const { return choices_; }
  bool is_variant() const { return variant_; }      ///< See variant().
  bool is_crossed() const { return crossed_; }      ///< See crossed().
  bool is_shorthand() const { return shorthand_; }  ///< See shorthand().
  /// See front(); empty for a knob fronts do not study.
  const std::optional<Front>& accuracy_front() const { return front_; }
  /// The shorthand flag's name: the spelling given to shorthand(), else "--" and the name with
  /// '_' as '-'.
  std::string flag() const {
    if (!flag_.empty()) return flag_;
    std::string f = "--" + name_;
    std::replace(f.begin(), f.end(), '_', '-');
    return f;
  }

  /// The knob's value in `p`, as JSON.
  nlohmann::json get(const P& p) const { return get_(p); }
  /// The default: the value in a default-constructed P.
  nlohmann::json default_value() const { return get_(P{}); }

  /// Checks `v` and stores it in `p`; throws ConfigError "<owner>: knob '<name>' must
  /// be ..., got <v>".
  void set(P& p, const nlohmann::json& v, std::string_view owner) const {
    check(v, owner);
    set_(p, v);
  }

  /// Throws ConfigError when `v` is not an acceptable value of this knob.
  void check(const nlohmann::json& v, std::string_view owner) const {
    const std::string why = why_not(v);
    if (!why.empty()) fail(owner, why);
  }

  /// Why `v` is not an acceptable value of this knob ("must be ..., got ..."); "" when it is.
  std::string why_not(const nlohmann::json& v) const {
    switch (type_) {
      case KnobType::Integer: {
        if (!v.is_number_integer()) return must_be("an integer", v);
        const bool in_range = v.is_number_unsigned()
                                  ? v.get<std::uint64_t>() <= ihi_ &&
                                        (ilo_ <= 0 || v.get<std::uint64_t>() >= std::uint64_t(ilo_))
                                  : v.get<long long>() >= ilo_ &&
                                        (v.get<long long>() < 0 || std::uint64_t(v.get<long long>()) <= ihi_);
        return in_range ? "" : out_of_range(v);
      }
      case KnobType::Number: {
        if (!word_.empty() && v.is_string() && v.get<std::string>() == word_) return "";
        if (!v.is_number()) return must_be(word_.empty() ? "a number" : "a number or \"" + word_ + "\"", v);
        const double x = v.get<double>();
        return (open_below_ ? x > lo_ : x >= lo_) && x <= hi_ ? "" : out_of_range(v);
      }
      case KnobType::Boolean:
        return v.is_boolean() ? "" : must_be("true or false", v);
      case KnobType::Choice: {
        if (v.is_string() || v.is_number_integer())
          for (const std::string& c : choices_)
            if (choice_spelling(v) == c) return "";
        return "must be one of " + choice_text() + ", got " + v.dump();
      }
    }
    return "";
  }

  /// Whether the knob's value in `p` is acceptable: check() without building JSON, cheap
  /// enough for a hot path (a gather validates its knobs on every call).
  bool valid(const P& p) const {
    switch (type_) {
      case KnobType::Number: {
        const std::optional<double> x = number_member_(p);
        return !x || ((open_below_ ? *x > lo_ : *x >= lo_) && *x <= hi_);
      }
      case KnobType::Boolean: return true;
      case KnobType::Integer:
      case KnobType::Choice: return valid_(p);
    }
    return false;
  }

  /// The accepted values in words: "[0, 64]", "(0, 1]", "[0, 3.4e38] or \"auto\"", "true|false",
  /// "midpoint|sah".
  std::string range_text() const {
    std::string lo, hi;
    switch (type_) {
      case KnobType::Integer:
        lo = std::to_string(ilo_);
        hi = std::to_string(ihi_);
        break;
      case KnobType::Number:
        lo = nlohmann::json(lo_).dump();
        hi = nlohmann::json(hi_).dump();
        // No upper end: "> 0.0 or "inf"".
        if (std::isinf(hi_)) return (open_below_ ? "> " : ">= ") + lo + (word_.empty() ? "" : " or \"" + word_ + "\"");
        break;
      case KnobType::Boolean: return "true|false";
      case KnobType::Choice: return choice_text();
    }
    std::string out = open_below_ ? "(" : "[";
    out.append(lo).append(", ").append(hi).append("]");
    if (!word_.empty()) out.append(" or \"").append(word_).append("\"");
    return out;
  }
  /// The word a number knob also accepts ("auto", "inf"), or "".
  const std::string& word() const { return word_; }
  /// "integer", "number", "boolean" or "choice".
  const char* type_name() const {
    switch (type_) {
      case KnobType::Integer: return "integer";
      case KnobType::Number: return "number";
      case KnobType::Boolean: return "boolean";
      case KnobType::Choice: return "choice";
    }
    return "";
  }

  /// The values tests try (see probes()).
  std::vector<nlohmann::json> probe_values() const {
    if (!probes_.empty()) return probes_;
    std::vector<nlohmann::json> out;
    switch (type_) {
      case KnobType::Integer: out = {nlohmann::json(ilo_), nlohmann::json(ihi_)}; break;
      case KnobType::Number:
        if (!open_below_) out.push_back(lo_);
        if (std::isfinite(hi_)) out.push_back(hi_);
        if (!word_.empty()) out.push_back(word_);
        break;
      case KnobType::Boolean: out = {false, true}; break;
      case KnobType::Choice: out.assign(choices_.begin(), choices_.end()); break;
    }
    const nlohmann::json d = default_value();
    if (std::find(out.begin(), out.end(), d) == out.end()) out.push_back(d);
    return out;
  }

 private:
  Knob(const char* name, KnobType type, const char* unit, const char* doc)
      : name_(name), type_(type), unit_(unit), doc_(doc) {}

  /// A float as the double of its shortest decimal spelling (0.2f as 0.2, not
  /// 0.20000000298023224), which converts back to the same float.
  template <std::floating_point T>
  static double shortest_double(T x) {
    if constexpr (std::is_same_v<T, float>) {
      if (!std::isfinite(x)) return double(x);
      char buf[32];
      const auto r = std::to_chars(buf, buf + sizeof buf, x);
      return std::strtod(std::string(buf, r.ptr).c_str(), nullptr);
    } else {
      return double(x);
    }
  }

  /// A choice as text: a string as itself, an integer as its digits (`--knob packet=8` reads
  /// the 8 as a number; the choice is spelled "8").
  static std::string choice_spelling(const nlohmann::json& v) {
    return v.is_string() ? v.get<std::string>() : v.dump();
  }

  std::string choice_text() const {
    std::string s;
    for (const std::string& c : choices_) {
      if (!s.empty()) s += '|';
      s += c;
    }
    return s;
  }
  [[noreturn]] void fail(std::string_view owner, const std::string& what) const {
    throw ConfigError(std::string(owner) + ": knob '" + name_ + "' " + what);
  }
  static std::string must_be(const std::string& want, const nlohmann::json& v) {
    return "must be " + want + ", got " + value_text(v);
  }
  std::string out_of_range(const nlohmann::json& v) const {
    const std::string range = range_text();
    return must_be(std::string(range[0] == '[' || range[0] == '(' ? "in " : "") + range, v);
  }
  /// A value as JSON, a non-finite number (from a struct filled in code) as nan or inf.
  static std::string value_text(const nlohmann::json& v) {
    if (v.is_number_float() && !std::isfinite(v.get<double>()))
      return std::isnan(v.get<double>()) ? "nan" : v.get<double>() > 0 ? "inf" : "-inf";
    return v.dump();
  }

  std::string name_;
  KnobType type_;
  std::string unit_;
  std::string doc_;
  double lo_ = 0.0, hi_ = 0.0;
  long long ilo_ = 0;
  unsigned long long ihi_ = 0;
  std::string word_;  // a number knob's other spelling ("auto", "inf"); "" when none
  std::vector<std::string> choices_;
  bool variant_ = false;
  bool crossed_ = false;
  bool open_below_ = false;
  bool shorthand_ = false;
  std::string flag_;
  std::optional<Front> front_;
  std::vector<nlohmann::json> probes_;
  std::function<nlohmann::json(const P&)> get_;
  std::function<void(P&, const nlohmann::json&)> set_;
  std::function<bool(const P&)> valid_;                          // integer and choice knobs
  std::function<std::optional<double>(const P&)> number_member_;  // number knobs; empty = the word
};

/// A knob as data, whatever struct it belongs to (AnyKnobTable::knob_infos()).
struct KnobInfo {
  std::string name;           ///< Spelling in JSON and on --knob.
  std::string flag;           ///< The shorthand flag ("--max-depth"); "" when it has none.
  KnobType type;              ///< Kind of value.
  bool crossed = false;       ///< See Knob::crossed().
  std::string unit;           ///< Unit ("" when none).
  std::string doc;            ///< One line: what it does.
  std::string range;          ///< Accepted values in words (Knob::range_text()).
  nlohmann::json default_value;
  std::optional<Front> front; ///< How fronts study it; empty when they do not.
};

/// A knob table seen without its struct: what the command line, the fronts, the docs and the
/// tests need from every table alike.
class AnyKnobTable {
 public:
  virtual ~AnyKnobTable() = default;
  /// Who the knobs belong to; the first word of every error.
  virtual const std::string& owner() const = 0;
  /// Knob names in display order.
  virtual std::vector<std::string> names() const = 0;
  /// Every knob as data, in display order.
  virtual std::vector<KnobInfo> knob_infos() const = 0;
  /// Every knob with its default filled in, from the given ones (an object or null); throws
  /// ConfigError, one line, on an unknown knob, a wrong type or a value out of range.
  virtual nlohmann::json complete(const nlohmann::json& given) const = 0;
  /// See KnobTable::describe().
  virtual nlohmann::json describe() const = 0;
  /// See KnobTable::markdown().
  virtual std::string markdown() const = 0;
  /// "its knobs: a, b" or "it has no knobs", for error messages.
  virtual std::string known_text() const = 0;
  /// Whether the table has a knob called `name`.
  bool has(std::string_view name) const {
    for (const std::string& n : names())
      if (n == name) return true;
    return false;
  }
};

/// Every knob of the parameter struct P, with the name of its owner (a structure, an
/// integrator) that starts every error message.
template <class P>
class KnobTable final : public AnyKnobTable {
 public:
  KnobTable(std::string owner, std::vector<Knob<P>> knobs) : owner_(std::move(owner)), knobs_(std::move(knobs)) {}

  /// Who the knobs belong to; the first word of every error.
  const std::string& owner() const override { return owner_; }
  /// The knobs, in display order.
  std::span<const Knob<P>> knobs() const { return knobs_; }
  /// The knob called `name`, or null.
  const Knob<P>* find(std::string_view name) const {
    for (const Knob<P>& k : knobs_)
      if (k.name() == name) return &k;
    return nullptr;
  }
  /// Knob names in display order.
  std::vector<std::string> names() const override {
    std::vector<std::string> out;
    for (const Knob<P>& k : knobs_) out.push_back(k.name());
    return out;
  }

  /// Every knob of `p`, spelled out (an object; empty for a struct without knobs).
  nlohmann::json to_json(const P& p) const {
    nlohmann::json j = nlohmann::json::object();
    for (const Knob<P>& k : knobs_) j[k.name()] = k.get(p);
    return j;
  }

  /// Only the knobs of `p` that differ from the defaults (what a scene file needs to say).
  nlohmann::json changed_json(const P& p) const {
    nlohmann::json j = nlohmann::json::object();
    for (const Knob<P>& k : knobs_)
      if (k.get(p) != k.default_value()) j[k.name()] = k.get(p);
    return j;
  }

  /// Overwrites the knobs present in `j` (an object, or null for none) and leaves the others.
  /// Unknown keys, wrong types and values out of range throw ConfigError, one line.
  void read(const nlohmann::json& j, P& p) const {
    if (j.is_null()) return;
    if (!j.is_object()) throw ConfigError(owner_ + ": knobs must be a JSON object, got " + j.dump());
    for (const auto& [key, value] : j.items()) {
      const Knob<P>* k = find(key);
      if (!k) throw ConfigError(owner_ + ": unknown knob '" + key + "' (" + known_text() + ")");
      k->set(p, value, owner_);
    }
  }

  /// The defaults with the knobs of `j` applied (see read()).
  P from_json(const nlohmann::json& j) const {
    P p{};
    read(j, p);
    return p;
  }

  /// Throws the same ConfigError as from_json would for a struct filled in code.
  void validate(const P& p) const {
    for (const Knob<P>& k : knobs_)
      if (!k.valid(p)) k.check(k.get(p), owner_);
  }

  nlohmann::json complete(const nlohmann::json& given) const override { return to_json(from_json(given)); }

  std::vector<KnobInfo> knob_infos() const override {
    std::vector<KnobInfo> out;
    for (const Knob<P>& k : knobs_)
      out.push_back({k.name(), k.is_shorthand() ? k.flag() : "", k.type(), k.is_crossed(), k.unit(),
                     k.doc(), k.range_text(), k.default_value(), k.accuracy_front()});
    return out;
  }

  /// "its knobs: a, b" or "it has no knobs", for error messages.
  std::string known_text() const override {
    if (knobs_.empty()) return "it has no knobs";
    std::string s;
    for (const Knob<P>& k : knobs_) {
      if (!s.empty()) s += ", ";
      s += k.name();
    }
    return "its knobs: " + s;
  }

  /// The table as data: per knob its name, type, default, range, unit, doc, flags and probes.
  nlohmann::json describe() const override {
    nlohmann::json out = nlohmann::json::array();
    for (const Knob<P>& k : knobs_) {
      nlohmann::json d = {{"name", k.name()},       {"type", k.type_name()},      {"default", k.default_value()},
                          {"range", k.range_text()}, {"unit", k.unit()},           {"doc", k.doc()},
                          {"variant", k.is_variant()}, {"crossed", k.is_crossed()}, {"probes", k.probe_values()}};
      if (k.type() == KnobType::Choice) d["choices"] = k.choices();
      if (k.is_shorthand()) d["flag"] = k.flag();
      out.push_back(d);
    }
    return out;
  }

  /// The knob reference as a Markdown table (generated into the docs).
  std::string markdown() const override {
    if (knobs_.empty()) return "No knobs.\n";
    std::string s = "| knob | type | default | range | unit | what it does |\n| --- | --- | --- | --- | --- | --- |\n";
    for (const Knob<P>& k : knobs_) {
      // Choices as `a`, `b`: a '|' would end the Markdown cell.
      std::string range;
      if (k.type() == KnobType::Choice || k.type() == KnobType::Boolean) {
        for (const std::string& c : k.type() == KnobType::Choice ? k.choices() : std::vector<std::string>{"true", "false"}) {
          if (!range.empty()) range += ", ";
          range.append("`").append(c).append("`");
        }
      } else {
        range = k.range_text();
      }
      s.append("| `").append(k.name()).append("` | ").append(k.type_name()).append(" | `");
      s.append(k.default_value().dump()).append("` | ").append(range).append(" | ");
      s.append(k.unit().empty() ? "-" : k.unit()).append(" | ").append(k.doc()).append(" |\n");
    }
    return s;
  }

 private:
  std::string owner_;
  std::vector<Knob<P>> knobs_;
};

/// A parameter struct with a knob table (a static knobs() returning it).
template <class P>
concept HasKnobTable = requires {
  { P::knobs() } -> std::same_as<const KnobTable<P>&>;
};


/// The JSON value of a knob given as text on the command line: a number or true/false when it
/// reads as one, else the text as a string. The knob table then checks it exactly as it checks
/// JSON, so `--knob` and JSON files give the same errors.
inline nlohmann::json knob_value_from_text(std::string_view text) {
  const nlohmann::json v = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (v.is_number() || v.is_boolean()) return v;
  return std::string(text);
}

/// Splits "NAME=VALUE" (the argument of --knob); throws ConfigError naming `flag` otherwise.
inline std::pair<std::string, nlohmann::json> parse_knob_assignment(std::string_view text,
                                                                   std::string_view flag = "--knob") {
  const auto eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0)
    throw ConfigError(std::string(flag) + ": expected NAME=VALUE, got '" + std::string(text) + "'");
  return {std::string(text.substr(0, eq)), knob_value_from_text(text.substr(eq + 1))};
}

}  // namespace knobs

/// nlohmann::json conversions of every parameter struct with a knob table, in any namespace:
/// `nlohmann::json(p)` and `j.get<P>()` go through the table.
template <class P>
struct nlohmann::adl_serializer<P, std::enable_if_t<knobs::HasKnobTable<P>>> {
  static void to_json(nlohmann::json& j, const P& p) { j = P::knobs().to_json(p); }
  static void from_json(const nlohmann::json& j, P& p) { p = P::knobs().from_json(j); }
};
