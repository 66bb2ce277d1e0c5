#include "integrators.h"

#include <array>
#include <stdexcept>

namespace bench {

namespace {

const std::array<const tracer::Integrator*, 2>& table() {
  static const std::array<const tracer::Integrator*, 2> kTable = {
      &tracer::whitted_integrator(),
      &tracer::spd_integrator(),
  };
  return kTable;
}

}  // namespace

std::span<const tracer::Integrator* const> integrators() { return table(); }

const tracer::Integrator* find_integrator(std::string_view name) {
  for (const tracer::Integrator* i : table())
    if (i->name == name) return i;
  return nullptr;
}

const tracer::Integrator& integrator_named(std::string_view name, const std::string& where) {
  if (const tracer::Integrator* i = find_integrator(name)) return *i;
  throw std::runtime_error(where + ": unknown integrator '" + std::string(name) +
                           "' (known: " + integrator_names() + ")");
}

std::string integrator_names() {
  std::string s;
  for (const tracer::Integrator* i : table()) s += (s.empty() ? "" : ", ") + std::string(i->name);
  return s;
}

}  // namespace bench
