#include "harness/accuracy_reference.h"

#include "integrators/integrators.h"
#include "harness/sweep_machine.h"

#include "input/file_read.h"
#include "input/json_read.h"
#include "tracer/render.h"
#include "tracer/scene_json.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace harness {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

/// Largest reference metadata file read from the cache (ours are a few kilobytes).
constexpr std::uint64_t kMaxReferenceMetaBytes = std::uint64_t(1) << 20;

std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

struct Rendered {
  tracer::Image image;
  tracer::RayCounts rays;
  double ms = 0.0;
};

Rendered render(const tracer::Scene& scene, const accel::AnyAccel& built, const std::string& integrator,
                const json& params, int width, int height, int threads) {
  tracer::RenderOptions o;
  o.threads = threads;
  o.width = width;
  o.height = height;
  tracer::RenderResult r = tracer::render(scene, built, o, integrators::named(integrator, "reference"), params);
  return {std::move(r.image), r.rays, r.render_ms};
}

json with_seed(json params, std::uint64_t seed) {
  params[knobs::kSeedKnob] = seed;
  return params;
}

/// Checks `built` against naive with the reference's knobs at the validation resolution.
void validate_structure(const tracer::Scene& scene, const accel::AnyAccel& built, const ReferenceSpec& spec,
                        const ReferenceOptions& options) {
  if (options.validate_width <= 0) return;
  const accel::AnyAccel naive = accel::make_accel("naive", json::object(), scene.geometry.primitive_bounds());
  const json params = spec.stochastic ? with_seed(spec.params, kReferenceSeedA) : spec.params;
  const Rendered a = render(scene, naive, spec.integrator, params, options.validate_width,
                            options.validate_height, options.threads);
  const Rendered b = render(scene, built, spec.integrator, params, options.validate_width,
                            options.validate_height, options.threads);
  if (a.image.content_hash() != b.image.content_hash() || !(a.rays == b.rays))
    throw std::runtime_error("reference: " + accel::name_of(built) + "'s image with " + params.dump() +
                             " differs from naive's at " + std::to_string(options.validate_width) + "x" +
                             std::to_string(options.validate_height) + "; not used for a reference");
}

/// Writes through a temporary file and a rename, so readers never see half a file.
template <class Write>
void write_atomic(const fs::path& path, Write write) {
  const fs::path tmp = path.string() + ".tmp" + std::to_string(::getpid());
  write(tmp.string());
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error("reference cache: cannot write " + path.string());
  }
}

/// The cached reference under `dir` with `key`, when both files are there and agree.
std::optional<AccuracyReference> read_cached(const fs::path& dir, const std::string& key, const ReferenceSpec& spec) {
  const fs::path meta = dir / (key + ".json"), pfm = dir / (key + ".pfm");
  std::error_code ec;
  if (!fs::is_regular_file(meta, ec) || !fs::is_regular_file(pfm, ec)) return std::nullopt;
  try {
    const json info = input::parse_json(input::read_file(meta.string(), kMaxReferenceMetaBytes, "reference metadata"));
    if (info.value("key", "") != key || info.value("version", 0) != kReferenceVersion ||
        info.value("spec", json()) != to_json(spec))
      return std::nullopt;
    AccuracyReference r;
    r.key = key;
    r.spec = spec;
    r.image = tracer::Image::read_pfm(pfm.string());
    if (r.image.width() != spec.width || r.image.height() != spec.height) return std::nullopt;
    const json& f = info.at("floor");
    r.floor.noise_rmse = f.at("noise_rmse").get<double>();
    r.floor.truncation_rmse = f.at("truncation_rmse").get<double>();
    r.floor.rmse = f.at("rmse").get<double>();
    r.floor.rel_mse = f.at("rel_mse").get<double>();
    r.floor.epsilon = f.at("epsilon").get<double>();
    r.info = info;
    r.from_cache = true;
    return r;
  } catch (const std::exception&) {
    return std::nullopt;  // unreadable or torn: render it again
  }
}

}  // namespace

json to_json(const ReferenceSpec& s) {
  json j = {{"integrator", s.integrator}, {"params", s.params}, {"stochastic", s.stochastic},
            {"width", s.width},           {"height", s.height}};
  if (!s.check.empty()) j["check"] = s.check;
  return j;
}

json to_json(const ReferenceFloor& f) {
  return {{"noise_rmse", f.noise_rmse}, {"truncation_rmse", f.truncation_rmse}, {"rmse", f.rmse},
          {"rel_mse", f.rel_mse},       {"epsilon", f.epsilon}};
}

std::string reference_key(const tracer::Scene& scene, const ReferenceSpec& spec, double epsilon) {
  const json all = {{"version", kReferenceVersion},
                    {"scene", tracer::scene_to_json(scene)},
                    {"spec", to_json(spec)},
                    {"epsilon", epsilon}};
  return tracer::hash_hex(fnv1a(all.dump()));
}

std::string default_reference_cache() {
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/accelbench/references";
  if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/accelbench/references";
  return ".accelbench-cache/references";
}

AccuracyReference obtain_reference(const tracer::Scene& scene, const accel::AnyAccel& built,
                                   const ReferenceSpec& spec, const ReferenceOptions& options) {
  const std::string key = reference_key(scene, spec, options.epsilon);
  const fs::path dir = options.cache_dir;
  if (!options.cache_dir.empty() && !options.refresh)
    if (auto cached = read_cached(dir, key, spec)) return std::move(*cached);

  const auto t0 = Clock::now();
  if (options.progress)
    std::fprintf(stderr, "fronts: rendering reference %s: %s %s at %dx%d%s\n", key.c_str(), spec.integrator.c_str(),
                 spec.params.dump().c_str(), spec.width, spec.height,
                 spec.stochastic ? ", two independent halves" : "");
  validate_structure(scene, built, spec, options);

  AccuracyReference r;
  r.key = key;
  r.spec = spec;
  json renders = json::array();
  const double eps = options.epsilon;
  Rendered a = render(scene, built, spec.integrator, spec.stochastic ? with_seed(spec.params, kReferenceSeedA) : spec.params,
                      spec.width, spec.height, options.threads);
  renders.push_back({{"what", spec.stochastic ? "half A" : "reference"}, {"render_ms", a.ms}, {"rays", a.rays}});
  double noise_rel = 0.0;
  if (spec.stochastic) {
    Rendered b = render(scene, built, spec.integrator, with_seed(spec.params, kReferenceSeedB), spec.width,
                        spec.height, options.threads);
    renders.push_back({{"what", "half B"}, {"render_ms", b.ms}, {"rays", b.rays}});
    const tracer::Image halves[2] = {a.image, b.image};
    r.image = tracer::mean_image(halves);
    // The mean of two independent halves deviates from its expectation by half their difference.
    const tracer::ImageError d = tracer::image_error(a.image, b.image, eps);
    r.floor.noise_rmse = d.rmse / 2.0;
    noise_rel = d.rel_mse / 4.0;
  } else {
    r.image = a.image;
  }
  double trunc_rel = 0.0;
  if (!spec.check.empty()) {
    json check = spec.params;
    check.update(spec.check);
    if (spec.stochastic) check[knobs::kSeedKnob] = kReferenceSeedA;
    const Rendered c = render(scene, built, spec.integrator, check, spec.width, spec.height, options.threads);
    renders.push_back({{"what", "check " + spec.check.dump()}, {"render_ms", c.ms}, {"rays", c.rays}});
    const tracer::ImageError d = tracer::image_error(c.image, a.image, eps);
    r.floor.truncation_rmse = d.rmse;
    trunc_rel = d.rel_mse;
  }
  r.floor.rmse = std::hypot(r.floor.noise_rmse, r.floor.truncation_rmse);
  r.floor.rel_mse = noise_rel + trunc_rel;
  r.floor.epsilon = eps;
  r.render_s = std::chrono::duration<double>(Clock::now() - t0).count();

  const json machine = machine_info();
  r.info = {{"key", key},
            {"version", kReferenceVersion},
            {"spec", to_json(spec)},
            {"floor", to_json(r.floor)},
            {"renders", renders},
            {"structure", accel::name_of(built)},
            {"made", utc_now_iso8601()},
            {"commit", machine.value("git_commit", "")},
            {"render_s", r.render_s}};
  for (int c = 0; c < 3; ++c)
    for (const auto& p : r.image.pixels())
      if (!std::isfinite(p[c])) throw std::runtime_error("reference " + key + ": the render has non-finite pixels");
  if (!options.cache_dir.empty()) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw std::runtime_error("reference cache: cannot create " + dir.string() + ": " + ec.message());
    write_atomic(dir / (key + ".pfm"), [&](const std::string& p) { r.image.write_pfm(p); });
    write_atomic(dir / (key + ".json"), [&](const std::string& p) {
      std::ofstream out(p);
      out << r.info.dump(2) << '\n';
      if (!out) throw std::runtime_error("reference cache: cannot write " + p);
    });
  }
  return r;
}

}  // namespace harness
