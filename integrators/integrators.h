#pragma once
// The one table of integrators: every renderer accelbench knows, by name. The command line, the
// sweeps and the tests look integrators up here and never switch on one; a new integrator is one
// file (its tracer::Integrator row) plus one line in integrators.cpp.

#include "tracer/render.h"

#include <nlohmann/json.hpp>

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace integrators {

/// Every integrator, in display order; the first ("whitted") is the default.
std::span<const tracer::Integrator* const> all();

/// The integrator called `name`, or nullptr.
const tracer::Integrator* find(std::string_view name);

/// The integrator called `name`; throws std::runtime_error "<where>: unknown integrator 'x'
/// (known: whitted, spd, ...)" otherwise.
const tracer::Integrator& named(std::string_view name, const std::string& where);

/// Every integrator's name, comma-separated, for --help and error messages.
std::string names();

/// The table as data: per integrator its name, description and knob table (describe()).
nlohmann::json table_json();

/// Every integrator's knob reference as Markdown (generated into docs/tracer.md).
std::string markdown();

/// The integrator of a render and its knobs, every default filled in.
struct Setup {
  const tracer::Integrator* integrator = nullptr;  ///< The table's row.
  nlohmann::json params;                           ///< Complete knobs (Integrator::params).
};

/// Chooses the integrator and completes its knobs. The integrator is `name` when not empty
/// (`name_where` names the flag in errors), else the scene's "integrator", else whitted. The
/// knobs are the scene's (when it chose the same integrator), then `overrides` on top
/// (`overrides_where` names them in errors). Throws std::runtime_error, one line naming the
/// scene's JSON pointer or the flag.
Setup resolve(const tracer::Scene& scene, const std::string& scene_label,
                                   const std::string& name, const std::string& name_where,
                                   const nlohmann::json& overrides,
                                   const std::string& overrides_where);

/// Parses NAME=VALUE items (e.g. --param k=100 filter=box max_radius=0.5) into a knob object:
/// VALUE is read as JSON when it parses (numbers, true/false), else as a string. Throws
/// std::runtime_error naming `flag` on an item without '=' or a repeated name.
nlohmann::json parse_knob_items(const std::vector<std::string>& items, const std::string& flag);

}  // namespace integrators
