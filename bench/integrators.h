#pragma once
// The one table of integrators: every renderer accelbench knows, by name. The command line, the
// sweeps and the tests look integrators up here and never switch on one; a new integrator is one
// file (its tracer::Integrator row) plus one line in integrators.cpp.

#include "tracer/render.h"

#include <span>
#include <string>
#include <string_view>

namespace bench {

/// Every integrator, in display order; the first ("whitted") is the default.
std::span<const tracer::Integrator* const> integrators();

/// The integrator called `name`, or nullptr.
const tracer::Integrator* find_integrator(std::string_view name);

/// The integrator called `name`; throws std::runtime_error "<where>: unknown integrator 'x'
/// (known: whitted, spd, ...)" otherwise.
const tracer::Integrator& integrator_named(std::string_view name, const std::string& where);

/// Every integrator's name, comma-separated, for --help and error messages.
std::string integrator_names();

}  // namespace bench
