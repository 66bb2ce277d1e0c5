#pragma once
// The accuracy knobs `accelbench fronts` can study: one row per (integrator, knob) whose knob
// table marks it with knobs::Front, walked from the integrator table. A new accuracy knob is
// one .front(...) in its integrator's table, never a special case here or in fronts.cpp.

#include <nlohmann/json.hpp>

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace harness {

/// One knob that trades accuracy for time.
struct AccuracyKnob {
  std::string integrator;  ///< Integrator the knob belongs to (integrators/integrators.h).
  std::string knob;        ///< Its name in the integrator's knob table.
  std::string unit;        ///< Unit of its values ("" when none).
  std::string doc;         ///< One line: what raising or lowering it does.
  /// The values a front tries by default, cheapest first.
  std::vector<nlohmann::json> values;
  /// The integrator of the reference render (the knob's own, or the consistent estimator that
  /// makes its reference).
  std::string reference_integrator;
  /// The reference's knobs: for its own integrator, knobs set so that this knob's error is
  /// negligible; for another integrator, that integrator's Integrator::reference_for_others.
  nlohmann::json reference;
  /// Knobs of a second, weaker reference (an empty object for none) whose difference from the
  /// reference estimates the reference's own truncation error (deterministic references).
  nlohmann::json check;
  /// The reference is stochastic: rendered twice with independent seeds, the reference is their
  /// mean and its noise is estimated from the two halves.
  bool stochastic_reference = false;
};

/// Every accuracy knob, integrator by integrator in the table's order.
std::span<const AccuracyKnob> accuracy_knobs();

/// The row for `knob` of `integrator`, or nullptr.
const AccuracyKnob* find_accuracy_knob(std::string_view integrator, std::string_view knob);

/// The accuracy knobs of `integrator`, comma-separated ("" when none), for messages.
std::string accuracy_knob_names(std::string_view integrator);

}  // namespace harness
