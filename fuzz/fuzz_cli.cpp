// Fuzz target: the parsers of command-line flag values (cli/cli_util.h: --resolution,
// --max-memory, --seed; harness/sweep_definition.h: sweep --resolution, --shard, SCENE items;
// cli/fronts_flags.h: every flag of `fronts` and `tune --max-error` at once). The input is
// lines; each line is one flag's value, given to every value parser, and line i also fills the
// fronts flag i modulo 8. Properties: a refusal names its flag first ("--flag: ..." or
// "SCENE: ..."); an accepted value is in the documented range.

#include "fuzz_check.h"

#include "cli/cli_util.h"
#include "cli/fronts_flags.h"
#include "harness/sweep_definition.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace {

/// Runs `parse`; a refusal must start with `flag` (its name) followed by ": ".
void expect_named(const std::string& flag, const std::function<void()>& parse) {
  try {
    parse();
  } catch (const std::exception& e) {
    const std::string message = e.what();
    fuzz::require(message.rfind(flag + ": ", 0) == 0, "a flag's refusal does not start with the flag", message);
  }
}

std::vector<std::string> lines_of(std::string_view text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= text.size() && out.size() < 64) {
    const std::size_t end = text.find('\n', start);
    out.emplace_back(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::string> lines = lines_of(fuzz::text_of(data, size));
  for (const std::string& v : lines) {
    expect_named("--resolution", [&] {
      int w = 0, h = 0;
      cli::parse_image_size(v, "--resolution", w, h);
      fuzz::require(w >= 1 && h >= 1 && w <= 65536 && h <= 65536, "a resolution out of range is accepted", v);
      cli::check_image_memory(w, h, 0, "--resolution");  // the default budget: names --resolution
    });
    expect_named("--max-memory", [&] { cli::parse_bytes(v, "--max-memory"); });
    expect_named("--seed", [&] { cli::parse_seed(v, "--seed"); });
    expect_named("--validate-resolution", [&] {
      const auto [w, h] = harness::parse_resolution(v, "--validate-resolution");
      fuzz::require(w >= 1 && h >= 1, "a sweep resolution out of range is accepted", v);
    });
    expect_named("--shard", [&] {
      const auto [i, n] = harness::parse_shard(v);
      fuzz::require(0 <= i && i < n, "a shard out of range is accepted", v);
    });
    expect_named("--values k", [&] {
      for (const nlohmann::json& value : cli::parse_knob_values_text(v, "--values k")) {
        fuzz::require(!value.is_number_float() || std::isfinite(value.get<double>()), "a value is not finite", v);
        // LO:HI:N needs LO > 0, so its integer values are at least 1.
        if (v.find(':') != std::string::npos && value.is_number_integer())
          fuzz::require(value.get<long long>() >= 1, "a log-spaced integer value is below LO", v);
      }
    });
  }

  // The fronts flags as one command line: a refusal names the flag it is about.
  cli::FrontsFlags f;
  f.scenes = {"five"};
  f.knobs = "max_depth";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& v = lines[i];
    switch (i % 8) {
      case 0: f.scenes.push_back(v); break;
      case 1: f.knobs = v; break;
      case 2: f.values.push_back(v); break;
      case 3: f.set.push_back(v); break;
      case 4: f.integrator = v; break;
      case 5: f.resolution = v; break;
      case 6: f.validate_resolution = v; break;
      default: f.seed = v; break;
    }
  }
  try {
    const harness::FrontsRequest r = cli::request_from_flags(f);
    fuzz::require(!r.groups.empty() && r.width >= 1 && r.height >= 1, "a fronts request without knobs or size");
  } catch (const std::exception& e) {
    const std::string message = e.what();
    fuzz::require(message.rfind("--", 0) == 0 || message.rfind("SCENE: ", 0) == 0,
                  "a fronts flag's refusal does not name its flag", message);
  }
  return 0;
}
