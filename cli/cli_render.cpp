// `accelbench render`: load a scene, build a structure over it, render, report the times and
// the ray counts, and write the image (PNG, PFM) and statistics (JSON).

#include "cli/cli_shorthand.h"
#include "cli/cli_util.h"
#include "cli/commands.h"
#include "integrators/integrators.h"

#include "accel/accel.h"
#include "tracer/build_accel.h"
#include "tracer/intersector.h"
#include "tracer/render.h"
#include "tracer/scene_io.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace cli {


namespace {

struct RenderFlags {
  std::string scene;
  std::string png;
  std::string pfm;
  std::vector<int> checkpoints;  ///< --checkpoints: earlier stages of a progressive integrator.
  std::string stats;
  std::string resolution;
  std::string accel;
  std::string max_memory;
  int threads = 0;
  float exposure = 0.0f;
  ShorthandValues structure_flags;   ///< --max-depth, --leaf-size, ...: the tables' shorthands.
  ShorthandValues integrator_flags;  ///< --precision: the integrators' shorthands.
  std::vector<std::string> knobs;  ///< --knob NAME=VALUE, any knob of the structure.
  std::string integrator;  ///< Integrator name (integrators/integrators.h); "" = the scene's, or whitted.
  bool spd = false;        ///< Shorthand for --integrator spd.
  std::vector<std::string> knob_items;  ///< --param NAME=VALUE: the integrator's knobs.
  /// auto | mixed: primitive dispatch (mixed measures the fast path).
  std::string dispatch = "auto";
};

std::string default_accel() {
  const auto names = accel::accel_names();
  return std::find(names.begin(), names.end(), "auto") != names.end() ? "auto" : "naive";
}

void require_extension(const std::string& path, const char* ext, const std::string& flag) {
  if (std::filesystem::path(path).extension() != ext)
    throw std::runtime_error(flag + ": expected a " + ext + " file name, got '" + path + "'");
}

/// Only the knobs the user gave, under the factory's names; the factory validates them with the
/// knob table's messages. The shorthand flags stand for --knob.
nlohmann::json knob_params(const RenderFlags& f) {
  nlohmann::json params = shorthand_knobs(f.structure_flags);
  for (const std::string& text : f.knobs) {
    auto [name, value] = knobs::parse_knob_assignment(text);
    if (params.contains(name))
      throw std::runtime_error("--knob: '" + name + "' is given twice");
    params[name] = std::move(value);
  }
  return params;
}

/// The integrator knobs of --param and the integrators' shorthand flags (--precision).
nlohmann::json integrator_overrides(const RenderFlags& f) {
  nlohmann::json knobs = integrators::parse_knob_items(f.knob_items, "--param");
  knobs.update(shorthand_knobs(f.integrator_flags, knobs));
  return knobs;
}

/// The integrator of --integrator (or its shorthand --spd), else the scene's, else whitted; its
/// knobs from the scene, --param and --precision.
integrators::Setup chosen_integrator(const RenderFlags& f, const tracer::Scene& scene) {
  if (f.spd && !f.integrator.empty() && f.integrator != "spd")
    throw std::runtime_error("--spd: is --integrator spd, but --integrator " + f.integrator +
                             " was given");
  const std::string name = f.spd ? "spd" : f.integrator;
  return integrators::resolve(scene, f.scene, name, "--integrator", integrator_overrides(f),
                            "--param");
}

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

std::string millions(double per_second) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f M", per_second / 1e6);
  return buf;
}

int run_render(const RenderFlags& f) {
  if (!f.png.empty()) require_extension(f.png, ".png", "-o");
  if (!f.pfm.empty()) require_extension(f.pfm, ".pfm", "--pfm");
  if (!f.stats.empty()) require_extension(f.stats, ".json", "--stats");
  if (!std::isfinite(f.exposure))
    throw std::runtime_error("--exposure: must be a finite number of stops");

  if (!f.checkpoints.empty() && f.pfm.empty()) throw std::runtime_error("--checkpoints: needs --pfm (their files sit beside it)");
  tracer::RenderOptions options;
  options.threads = f.threads;
  options.checkpoints = f.checkpoints;
  if (!f.resolution.empty())
    parse_image_size(f.resolution, "--resolution", options.width, options.height);
  accel::BuildLimits limits;
  if (!f.max_memory.empty()) limits.max_memory_bytes = parse_bytes(f.max_memory, "--max-memory");

  const std::string accel_name = f.accel.empty() ? default_accel() : f.accel;
  const auto names = accel::accel_names();
  if (std::find(names.begin(), names.end(), accel_name) == names.end()) {
    std::string known;
    for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
    throw std::runtime_error("--accel: unknown structure '" + accel_name + "' (known: " + known +
                             ")");
  }
  const nlohmann::json params = knob_params(f);
  integrator_overrides(f);  // its errors before the scene is read

  tracer::Scene scene = tracer::load_scene_file(f.scene, limits.max_memory_bytes);
  scene.geometry.force_mixed = f.dispatch == "mixed";
  options.limits = limits;
  const integrators::Setup setup = chosen_integrator(f, scene);
  const tracer::Integrator& integrator = *setup.integrator;
  if (!f.checkpoints.empty() && !integrator.stage_knob)
    throw std::runtime_error("--checkpoints: integrator " + std::string(integrator.name) + " is not progressive");
  const int width = options.width ? options.width : scene.camera.width;
  const int height = options.height ? options.height : scene.camera.height;
  const int threads = tracer::resolve_threads(f.threads);
  // The image is allocated before the first pixel: refuse one that cannot fit, naming the flag
  // (or the scene) that asked for it.
  check_image_memory(width, height, limits.max_memory_bytes,
                     options.width ? std::string("--resolution") : f.scene + ": /camera/resolution");

  if (integrator.check) integrator.check(scene, options, setup.params);
  // Built before anything is printed, so that a bad knob is the only line of output.
  const auto boxes = scene.geometry.primitive_bounds();
  const auto build_start = std::chrono::steady_clock::now();
  accel::AnyAccel structure = tracer::build_accel(accel_name, params, scene.geometry, boxes, limits);
  const double build_ms = ms_since(build_start);
  const accel::BuildStats& build = accel::stats_of(structure);

  std::printf("scene    %s: %s\n", f.scene.c_str(), describe_scene(scene).c_str());
  std::printf("image    %dx%d, %d sample%s per pixel, %d thread%s\n", width, height,
              scene.camera.samples_per_pixel, scene.camera.samples_per_pixel == 1 ? "" : "s",
              threads, threads == 1 ? "" : "s");
  std::printf("accel    %s %s: built in %.3f ms, %llu nodes, %.1f KiB\n",
              accel::name_of(structure).c_str(), accel::params_of(structure).dump().c_str(),
              build_ms, static_cast<unsigned long long>(build.nodes),
              double(build.memory_bytes) / 1024.0);
  std::fflush(stdout);

  std::printf("integrator %s: %s\n", std::string(integrator.name).c_str(),
              std::string(integrator.description).c_str());
  if (!setup.params.empty()) std::printf("knobs    %s\n", setup.params.dump().c_str());
  std::fflush(stdout);
  const tracer::RenderResult result =
      tracer::render(scene, structure, options, integrator, setup.params);
  const tracer::RayCounts& rays = result.rays;
  const double seconds = result.render_ms / 1e3;
  const double rays_per_s = seconds > 0 ? double(rays.total()) / seconds : 0.0;
  const double primary_per_s = seconds > 0 ? double(rays.eye) / seconds : 0.0;
  std::printf("render   %.3f ms\n", result.render_ms);
  std::printf(
      "rays     eye %llu (hits %llu), reflection %llu, refraction %llu, shadow %llu%s; total %llu\n",
      static_cast<unsigned long long>(rays.eye), static_cast<unsigned long long>(rays.eye_hits),
      static_cast<unsigned long long>(rays.reflection),
      static_cast<unsigned long long>(rays.refraction),
      static_cast<unsigned long long>(rays.shadow),
      rays.gather + rays.photon == 0
          ? ""
          : (", gather " + std::to_string(rays.gather) + ", photon " + std::to_string(rays.photon))
                .c_str(),
      static_cast<unsigned long long>(rays.total()));
  std::printf("speed    %srays/s (all rays, shadow rays included), %srays/s primary\n",
              millions(rays_per_s).c_str(), millions(primary_per_s).c_str());
  if (integrator.summary) std::printf("%s", integrator.summary(result.stats).c_str());

  if (!f.png.empty()) result.image.write_png(f.png, f.exposure);
  if (!f.pfm.empty()) result.image.write_pfm(f.pfm);
  std::vector<std::string> written;
  for (const auto& [stage, image] : result.checkpoints) {
    // FILE.pfm -> FILE.STAGE.pfm
    const std::string path = f.pfm.substr(0, f.pfm.size() - 4) + "." + std::to_string(stage) + ".pfm";
    image.write_pfm(path);
    written.push_back(path);
  }

  if (!f.stats.empty()) {
    // The counting pass: same image, with traversal counters on; never the timed one.
    tracer::RenderOptions counting = options;
    counting.count_traversal = true;
    const tracer::RenderResult counted =
        tracer::render(scene, structure, counting, integrator, setup.params);
    if (counted.image.content_hash() != result.image.content_hash() ||
        !(counted.rays == result.rays))
      throw std::runtime_error("the counting pass rendered a different image than the timed pass");
    nlohmann::json stats = {
        {"scene", f.scene},
        {"resolution", {width, height}},
        {"samples_per_pixel", scene.camera.samples_per_pixel},
        {"integrator", integrator.name},
        {"integrator_params", setup.params},
        {"integrator_stats", {{"timed", result.stats}, {"counting", counted.stats}}},
        {"meshes", mesh_stats_json(scene)},
        {"dispatch",
         scene.geometry.kind_set() == tracer::KindSet::SpheresOnly ? "spheres_only" : "mixed"},
        {"threads", threads},
        {"accel", accel::name_of(structure)},
        {"params", accel::params_of(structure)},
        {"build", build},
        {"traversal", counted.traversal},
        {"rays", rays},
        {"timings", {{"build_ms", build_ms}, {"render_ms", result.render_ms}}},
        {"rays_per_second", rays_per_s},
        {"primary_rays_per_second", primary_per_s},
        {"image_hash", tracer::hash_hex(result.image.content_hash())}};
    std::ofstream out(f.stats);
    out << stats.dump(2) << '\n';
    if (!out) throw std::runtime_error("--stats: cannot write '" + f.stats + "'");
  }
  for (const std::string* path : {&f.png, &f.pfm, &f.stats})
    if (!path->empty()) std::printf("wrote    %s\n", path->c_str());
  for (const std::string& path : written) std::printf("wrote    %s\n", path.c_str());
  return 0;
}

}  // namespace

void add_render_command(CLI::App& app, int& exit_code) {
  auto flags = std::make_shared<RenderFlags>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene through one acceleration structure");
  cmd->add_option("SCENE", flags->scene, "Scene file (.json or .nff)")->required();
  cmd->add_option("-o,--output", flags->png, "PNG image to write (sRGB, 8 bit)");
  cmd->add_option("--pfm", flags->pfm, "Linear float image to write (PFM)");
  cmd->add_option("--checkpoints", flags->checkpoints,
                  "Also write a progressive integrator's images after these stages (ppm: passes), each as "
                  "PFM-STEM.STAGE.pfm beside --pfm; stages not below its own count are skipped")
      ->delimiter(',')
      ->check(CLI::Range(1, 1 << 30));
  cmd->add_option("--threads", flags->threads, "Render threads; 0 = all cores")
      ->check(CLI::Range(0, 4096));
  cmd->add_option("--resolution", flags->resolution,
                  "Image size WIDTHxHEIGHT, overriding the scene's");
  cmd->add_option("--exposure", flags->exposure,
                  "Exposure of the PNG in stops (EV); the PFM is not scaled");
  cmd->add_option(
      "--accel", flags->accel,
      "Acceleration structure (default: auto when built, else naive); one of " + [] {
        std::string s;
        for (const std::string& n : accel::accel_names()) s += (s.empty() ? "" : ", ") + n;
        return s;
      }());
  add_shorthand_flags(*cmd, structure_shorthand_flags(), flags->structure_flags, /*list=*/false);
  cmd->add_option("--knob", flags->knobs,
                  "Any structure knob as NAME=VALUE, repeatable (see `accelbench structures`)");
  cmd->add_option(
      "--max-memory", flags->max_memory,
      "Memory budget of the build, bytes with optional K/M/G suffix (default: 25% of RAM)");
  cmd->add_option(
      "--stats", flags->stats,
      "Statistics JSON to write (adds an untimed counting pass for traversal counters)");
  cmd->add_option("--integrator", flags->integrator,
                  "Integrator (default whitted); one of " + integrators::names());
  cmd->add_option("--param", flags->knob_items,
                  "Integrator knob NAME=VALUE, repeatable (over the scene's \"integrator\" "
                  "knobs), e.g. --param global_photons=200000 --param filter=box")
      ->allow_extra_args(false);
  cmd->add_flag("--spd", flags->spd,
                "Shorthand for --integrator spd: the SPD test rules (rays at pixel corners, tree "
                "depth 5, NFF shading; for .nff scenes)");
  add_shorthand_flags(*cmd, integrator_shorthand_flags(), flags->integrator_flags, /*list=*/false);
  cmd->add_option(
         "--dispatch", flags->dispatch,
         "Primitive dispatch: auto (sphere-only scenes take the spheres-only path) | mixed")
      ->check(CLI::IsMember({"auto", "mixed"}));
  cmd->callback([flags, &exit_code] { exit_code = run_render(*flags); });
}

}  // namespace cli
