#include "harness/accuracy_knobs.h"

#include "integrators/integrators.h"

namespace harness {

namespace {

nlohmann::json parse_or_empty(const char* text) {
  return text && *text ? nlohmann::json::parse(text) : nlohmann::json::object();
}

std::vector<AccuracyKnob> collect() {
  std::vector<AccuracyKnob> out;
  for (const tracer::Integrator* integrator : integrators::all()) {
    for (const knobs::KnobInfo& k : integrator->knob_table().knob_infos()) {
      if (!k.front) continue;
      const knobs::Front& f = *k.front;
      AccuracyKnob row;
      row.integrator = integrator->name;
      row.knob = k.name;
      row.unit = k.unit;
      row.doc = k.doc;
      const nlohmann::json values = nlohmann::json::parse(f.values);
      row.values.assign(values.begin(), values.end());
      if (f.reference_integrator.empty()) {
        row.reference_integrator = integrator->name;
        row.reference = parse_or_empty(f.reference);
      } else {
        const tracer::Integrator& other = integrators::named(f.reference_integrator, std::string(integrator->name));
        row.reference_integrator = other.name;
        row.reference = parse_or_empty(other.reference_for_others);
      }
      row.check = parse_or_empty(f.check);
      row.stochastic_reference = f.stochastic;
      out.push_back(std::move(row));
    }
  }
  return out;
}

}  // namespace

std::span<const AccuracyKnob> accuracy_knobs() {
  static const std::vector<AccuracyKnob> rows = collect();
  return rows;
}

const AccuracyKnob* find_accuracy_knob(std::string_view integrator, std::string_view knob) {
  for (const AccuracyKnob& k : accuracy_knobs())
    if (k.integrator == integrator && k.knob == knob) return &k;
  return nullptr;
}

std::string accuracy_knob_names(std::string_view integrator) {
  std::string s;
  for (const AccuracyKnob& k : accuracy_knobs())
    if (k.integrator == integrator) s += (s.empty() ? "" : ", ") + k.knob;
  return s;
}

}  // namespace harness
