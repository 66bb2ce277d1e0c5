#include "integrators/integrators.h"

#include "photon/photon_integrator.h"
#include "photon/ppm_integrator.h"

#include <array>
#include <stdexcept>

namespace integrators {

namespace {

const std::array<const tracer::Integrator*, 4>& table() {
  static const std::array<const tracer::Integrator*, 4> kTable = {
      &tracer::whitted_integrator(),
      &tracer::spd_integrator(),
      &photon::photon_integrator(),
      &photon::ppm_integrator(),
  };
  return kTable;
}

}  // namespace

std::span<const tracer::Integrator* const> all() { return table(); }

const tracer::Integrator* find(std::string_view name) {
  for (const tracer::Integrator* i : table())
    if (i->name == name) return i;
  return nullptr;
}

const tracer::Integrator& named(std::string_view name, const std::string& where) {
  if (const tracer::Integrator* i = find(name)) return *i;
  throw std::runtime_error(where + ": unknown integrator '" + std::string(name) +
                           "' (known: " + names() + ")");
}

Setup resolve(const tracer::Scene& scene, const std::string& scene_label,
                                   const std::string& name, const std::string& name_where,
                                   const nlohmann::json& overrides,
                                   const std::string& overrides_where) {
  Setup setup;
  const std::string& scene_name = scene.integrator.name;
  if (!name.empty()) {
    setup.integrator = &named(name, name_where);
  } else if (!scene_name.empty()) {
    setup.integrator = &named(scene_name, scene_label + ": /integrator/name");
  } else {
    setup.integrator = &named("whitted", "default");
  }
  nlohmann::json knobs = nlohmann::json::object();
  if (scene_name == setup.integrator->name && scene.integrator.knobs.is_object()) {
    knobs = scene.integrator.knobs;
    try {
      setup.integrator->params(knobs);
    } catch (const std::exception& e) {
      throw std::runtime_error(scene_label + ": /integrator: " + e.what());
    }
  }
  if (overrides.is_object())
    for (auto it = overrides.begin(); it != overrides.end(); ++it) knobs[it.key()] = it.value();
  try {
    setup.params = setup.integrator->params(knobs);
  } catch (const std::exception& e) {
    throw std::runtime_error(overrides_where + ": " + e.what());
  }
  return setup;
}

nlohmann::json parse_knob_items(const std::vector<std::string>& items, const std::string& flag) {
  nlohmann::json knobs = nlohmann::json::object();
  for (const std::string& item : items) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      throw std::runtime_error(flag + ": expected NAME=VALUE, got '" + item + "'");
    const std::string key = item.substr(0, eq), text = item.substr(eq + 1);
    if (knobs.contains(key)) throw std::runtime_error(flag + ": '" + key + "' is given twice");
    nlohmann::json value = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
    knobs[key] = value.is_discarded() ? nlohmann::json(text) : value;
  }
  return knobs;
}

nlohmann::json table_json() {
  nlohmann::json out = nlohmann::json::array();
  for (const tracer::Integrator* i : table())
    out.push_back({{"name", i->name}, {"description", i->description}, {"knobs", i->knob_table().describe()}});
  return out;
}

std::string markdown() {
  std::string md;
  for (const tracer::Integrator* i : table())
    md += "### `" + std::string(i->name) + "`\n\n" + std::string(i->description) + ".\n\n" + i->knob_table().markdown() + "\n";
  return md;
}

std::string names() {
  std::string s;
  for (const tracer::Integrator* i : table()) s += (s.empty() ? "" : ", ") + std::string(i->name);
  return s;
}

}  // namespace integrators
