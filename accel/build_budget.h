#pragma once
// Memory accounting for tree builders: every array a builder grows goes through a BuildBudget,
// which refuses (knobs::ConfigError naming the knobs to change) before the bytes held would pass the
// budget, so a runaway build stops cleanly instead of exhausting the machine's memory.

#include "accel.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace accel {

class BuildBudget {
 public:
  /// `structure` and `advice` make up the error: "<structure>: build needs more than <budget>
  /// (--max-memory); <advice>".
  BuildBudget(std::uint64_t budget_bytes, std::string structure, std::string advice)
      : budget_(budget_bytes), structure_(std::move(structure)), advice_(std::move(advice)) {}

  /// Makes room for `extra` more elements in `v`, growing its capacity geometrically. During a
  /// reallocation the old and the new block are both held, so that peak is what is checked.
  template <class T>
  void reserve_more(std::vector<T>& v, std::size_t extra) {
    const std::uint64_t need = std::uint64_t(v.size()) + extra;
    if (need <= v.capacity()) return;
    const std::uint64_t old_bytes = std::uint64_t(v.capacity()) * sizeof(T);
    // Double, or near the budget take what is left (growing by `need` alone would turn the last
    // few pushes before the limit into a quadratic copy).
    const std::uint64_t left = budget_ > held_ ? (budget_ - held_) / sizeof(T) : 0;
    if (need > left) fail();
    const std::uint64_t cap = std::min(std::max<std::uint64_t>(need, 2 * std::uint64_t(v.capacity())), left);
    v.reserve(std::size_t(cap));
    held_ += std::uint64_t(v.capacity()) * sizeof(T) - old_bytes;
  }

  /// Forgets `v`'s bytes (call after freeing or handing it over elsewhere).
  template <class T>
  void release(std::vector<T>& v) {
    held_ -= std::uint64_t(v.capacity()) * sizeof(T);
    std::vector<T>().swap(v);
  }

  /// Bytes currently held by the arrays grown through this budget.
  std::uint64_t held_bytes() const { return held_; }

 private:
  [[noreturn]] void fail() const {
    char size[32];
    const double gib = double(budget_) / double(std::uint64_t(1) << 30);
    if (gib >= 1.0)
      std::snprintf(size, sizeof size, "%.1f GiB", gib);
    else
      std::snprintf(size, sizeof size, "%.1f MiB", double(budget_) / double(1 << 20));
    throw knobs::ConfigError(structure_ + ": build needs more than " + size + " (--max-memory); " + advice_);
  }

  std::uint64_t budget_;
  std::uint64_t held_ = 0;
  std::string structure_;
  std::string advice_;
};

}  // namespace accel
