#pragma once
// The accuracy knobs `accelbench fronts` can study: one row per (integrator, knob), with the
// values a front tries by default (log-spaced over the knob's useful range) and how the
// reference for that knob is made. Like the integrator table, this is data: a new accuracy knob
// is one row here, never a special case elsewhere.

#include <nlohmann/json.hpp>

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace bench {

/// One knob that trades accuracy for time.
struct AccuracyKnob {
  std::string_view integrator;  ///< Integrator the knob belongs to (bench/integrators.h).
  std::string_view knob;        ///< Its name among the integrator's knobs.
  std::string_view unit;        ///< Unit of its values ("" when none).
  std::string_view doc;         ///< One line: what raising or lowering it does.
  /// The values a front tries by default, cheapest first (JSON array).
  const char* values;
  /// The integrator of the reference render; "" = the knob's own integrator. A consistent
  /// estimator (progressive photon mapping) makes the reference for a biased one's knobs.
  std::string_view reference_integrator;
  /// The reference's knobs (JSON object): for its own integrator, knobs set so that this knob's
  /// error is negligible (the studied knob among them); for another integrator, all its knobs.
  const char* reference;
  /// Knobs of a second, weaker reference render (JSON object, "" for none) whose difference from
  /// the reference estimates the reference's own truncation error (deterministic references).
  const char* check;
  /// The reference is stochastic: it is rendered twice with independent seeds ("seed" knob), the
  /// reference is their mean and its noise is estimated from the two halves.
  bool stochastic_reference;
};

/// Every accuracy knob, in display order.
std::span<const AccuracyKnob> accuracy_knobs();

/// The row for `knob` of `integrator`, or nullptr.
const AccuracyKnob* find_accuracy_knob(std::string_view integrator, std::string_view knob);

/// The accuracy knobs of `integrator`, comma-separated ("" when none), for messages.
std::string accuracy_knob_names(std::string_view integrator);

/// The default values of a row, parsed.
std::vector<nlohmann::json> default_values(const AccuracyKnob& k);

}  // namespace bench
