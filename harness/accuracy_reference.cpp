#include "harness/accuracy_reference.h"

#include "harness/analytic_reference.h"

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
  std::vector<std::pair<int, tracer::Image>> checkpoints;  ///< Earlier stages' images.
};

Rendered render(const tracer::Scene& scene, const accel::AnyAccel& built, const std::string& integrator,
                const json& params, int width, int height, int threads, std::vector<int> checkpoints = {}) {
  tracer::RenderOptions o;
  o.threads = threads;
  o.width = width;
  o.height = height;
  o.checkpoints = std::move(checkpoints);
  tracer::RenderResult r = tracer::render(scene, built, o, integrators::named(integrator, "reference"), params);
  return {std::move(r.image), r.rays, r.render_ms, std::move(r.checkpoints)};
}

/// A progressive spec's stage count (its stage knob, the integrator's default when not given).
long long stages_of(const ReferenceSpec& spec) {
  return integrators::named(spec.integrator, "reference").params(spec.params).at(spec.stage_knob).get<long long>();
}

/// The image of `r` after `stages` stages (its final image at its own count).
const tracer::Image& stage_image(const Rendered& r, long long stages, long long total, const std::string& what) {
  if (stages == total) return r.image;
  for (const auto& [at, image] : r.checkpoints)
    if (at == stages) return image;
  throw std::runtime_error("reference: the " + what + " render returned no image after " + std::to_string(stages) +
                           " stages");
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
    r.floor.bias_rmse = f.value("bias_rmse", 0.0);
    r.floor.bias_rmse_estimate = f.value("bias_rmse_estimate", 0.0);
    r.floor.bias_order = f.value("bias_order", 0.0);
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
  if (!s.stage_knob.empty()) {
    j["stage_knob"] = s.stage_knob;
    j["bias_order"] = s.bias_order;
    j["estimator"] = estimator_name(s.estimator);
  }
  return j;
}

json to_json(const ReferenceFloor& f) {
  return {{"noise_rmse", f.noise_rmse}, {"truncation_rmse", f.truncation_rmse},
          {"bias_rmse", f.bias_rmse},   {"bias_rmse_estimate", f.bias_rmse_estimate},
          {"bias_order", f.bias_order},
          {"rmse", f.rmse},             {"rel_mse", f.rel_mse},
          {"epsilon", f.epsilon}};
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

/// Fills r.info and writes r to the cache (when there is one).
static void store(AccuracyReference& r, const json& renders, const accel::AnyAccel& built, double render_s,
           const ReferenceOptions& options);

static AccuracyReference obtain_progressive(const tracer::Scene& scene, const accel::AnyAccel& built,
                                            const ReferenceSpec& spec, const ReferenceOptions& options);

/// One reference at exactly `spec`'s knobs: from the cache, or rendered and stored.
static AccuracyReference obtain_level(const tracer::Scene& scene, const accel::AnyAccel& built, const ReferenceSpec& spec,
                               const ReferenceOptions& options) {
  if (!spec.stage_knob.empty()) return obtain_progressive(scene, built, spec, options);
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
  store(r, renders, built, r.render_s, options);
  return r;
}

static void store(AccuracyReference& r, const json& renders, const accel::AnyAccel& built, double render_s,
                  const ReferenceOptions& options) {
  const std::string& key = r.key;
  const fs::path dir = options.cache_dir;
  const json machine = machine_info();
  r.info = {{"key", key},
            {"version", kReferenceVersion},
            {"spec", to_json(r.spec)},
            {"floor", to_json(r.floor)},
            {"renders", renders},
            {"structure", accel::name_of(built)},
            {"made", utc_now_iso8601()},
            {"commit", machine.value("git_commit", "")},
            {"render_s", render_s}};
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
}

namespace {

/// The two halves of a progressive reference, each with its images at N, N/8 and (when N
/// divides) N/64 stages, and how they were made.
struct Halves {
  HalfStages half[2];
  json renders = json::array();
  double render_s = 0.0;  ///< Wall time that rendered them, s (when they were made).
  bool from_cache = false;
};

/// The key of a progressive reference's halves: everything that decides their pixels, i.e. its
/// spec less the estimator, so plain and Richardson references share one pair of renders, and a
/// change to how the floor is estimated needs none.
std::string halves_key(const tracer::Scene& scene, const ReferenceSpec& spec) {
  json s = to_json(spec);
  s.erase("estimator");
  const json all = {{"version", kReferenceVersion}, {"scene", tracer::scene_to_json(scene)}, {"halves", s}};
  return tracer::hash_hex(fnv1a(all.dump()));
}

/// The stages kept of N: N, N/8 and, when N divides by 64, N/64.
std::vector<long long> kept_stages(long long n) {
  std::vector<long long> out = {n, n / kStageRatio};
  if (n % (kStageRatio * kStageRatio) == 0) out.push_back(n / (kStageRatio * kStageRatio));
  return out;
}

fs::path stage_file(const fs::path& dir, const std::string& key, int half, long long stage) {
  return dir / (key + (half == 0 ? ".A." : ".B.") + std::to_string(stage) + ".pfm");
}

tracer::Image& stage_slot(HalfStages& h, int index) { return index == 0 ? h.n : index == 1 ? h.n8 : h.n64; }

std::optional<Halves> read_cached_halves(const fs::path& dir, const std::string& key, const ReferenceSpec& spec,
                                         long long n) {
  const fs::path meta = dir / (key + ".halves.json");
  std::error_code ec;
  if (!fs::is_regular_file(meta, ec)) return std::nullopt;
  try {
    const json info = input::parse_json(input::read_file(meta.string(), kMaxReferenceMetaBytes, "reference metadata"));
    if (info.value("key", "") != key || info.value("version", 0) != kReferenceVersion) return std::nullopt;
    Halves h;
    const std::vector<long long> stages = kept_stages(n);
    for (int half = 0; half < 2; ++half)
      for (std::size_t i = 0; i < stages.size(); ++i) {
        tracer::Image image = tracer::Image::read_pfm(stage_file(dir, key, half, stages[i]).string());
        if (image.width() != spec.width || image.height() != spec.height) return std::nullopt;
        stage_slot(h.half[half], int(i)) = std::move(image);
      }
    h.renders = info.at("renders");
    h.render_s = info.at("render_s").get<double>();
    h.from_cache = true;
    return h;
  } catch (const std::exception&) {
    return std::nullopt;  // unreadable or torn: render them again
  }
}

}  // namespace

// A progressive reference: its two halves with their earlier stages (cached on their own), and
// the estimator's image and floor computed from them on every use.
static AccuracyReference obtain_progressive(const tracer::Scene& scene, const accel::AnyAccel& built,
                                            const ReferenceSpec& spec, const ReferenceOptions& options) {
  const std::string key = reference_key(scene, spec, options.epsilon);
  const long long n = stages_of(spec);
  const long long divisor = estimator_divisor(spec.estimator);
  if (n % divisor != 0)
    throw std::runtime_error("reference: a " + std::string(estimator_name(spec.estimator)) + " reference needs " +
                             spec.stage_knob + " divisible by " + std::to_string(divisor) + ", got " +
                             std::to_string(n));
  const std::string hkey = halves_key(scene, spec);
  const fs::path dir = options.cache_dir;
  std::optional<Halves> halves;
  if (!options.cache_dir.empty() && !options.refresh) halves = read_cached_halves(dir, hkey, spec, n);
  if (!halves) {
    const auto t0 = Clock::now();
    if (options.progress)
      std::fprintf(stderr, "fronts: rendering reference %s: %s %s at %dx%d, two independent halves\n", key.c_str(),
                   spec.integrator.c_str(), spec.params.dump().c_str(), spec.width, spec.height);
    validate_structure(scene, built, spec, options);
    halves.emplace();
    const std::vector<long long> stages = kept_stages(n);
    const std::vector<int> checkpoints(stages.begin() + 1, stages.end());
    for (int half = 0; half < 2; ++half) {
      const Rendered r = render(scene, built, spec.integrator, with_seed(spec.params, half == 0 ? kReferenceSeedA : kReferenceSeedB),
                                spec.width, spec.height, options.threads, checkpoints);
      halves->renders.push_back({{"what", half == 0 ? "half A" : "half B"}, {"render_ms", r.ms}, {"rays", r.rays}});
      for (std::size_t i = 0; i < stages.size(); ++i)
        stage_slot(halves->half[half], int(i)) = stage_image(r, stages[i], n, "reference");
    }
    halves->render_s = std::chrono::duration<double>(Clock::now() - t0).count();
    if (!options.cache_dir.empty()) {
      std::error_code ec;
      fs::create_directories(dir, ec);
      if (ec) throw std::runtime_error("reference cache: cannot create " + dir.string() + ": " + ec.message());
      for (int half = 0; half < 2; ++half)
        for (std::size_t i = 0; i < stages.size(); ++i)
          write_atomic(stage_file(dir, hkey, half, stages[i]),
                       [&](const std::string& p) { stage_slot(halves->half[half], int(i)).write_pfm(p); });
      const json meta = {{"key", hkey},   {"version", kReferenceVersion},    {"renders", halves->renders},
                         {"stages", stages}, {"render_s", halves->render_s}, {"made", utc_now_iso8601()}};
      write_atomic(dir / (hkey + ".halves.json"), [&](const std::string& p) {
        std::ofstream out(p);
        out << meta.dump(2) << '\n';
        if (!out) throw std::runtime_error("reference cache: cannot write " + p);
      });
    }
  }
  const ProgressiveReference p =
      progressive_reference(halves->half[0], halves->half[1], spec.bias_order, spec.estimator, options.epsilon);
  AccuracyReference r;
  r.key = key;
  r.spec = spec;
  r.image = p.image;
  r.floor.noise_rmse = std::sqrt(p.noise_mse);
  r.floor.bias_rmse = std::sqrt(p.bias_mse.upper);
  r.floor.bias_rmse_estimate = std::sqrt(p.bias_mse.value);
  r.floor.bias_order = p.bias_order;
  r.floor.rmse = std::sqrt(p.noise_mse + p.bias_mse.upper);
  r.floor.rel_mse = p.noise_rel + p.bias_rel.upper;
  r.floor.epsilon = options.epsilon;
  r.from_cache = halves->from_cache;
  r.render_s = halves->from_cache ? 0.0 : halves->render_s;
  // The reference as a file of its own too (its image and floor), for readers of the cache.
  store(r, halves->renders, built, halves->render_s, options);
  r.info["halves"] = hkey;
  return r;
}

AccuracyReference obtain_reference(const tracer::Scene& scene, const accel::AnyAccel& built,
                                   const ReferenceSpec& spec, const ReferenceOptions& options) {
  // A consistent estimator of the full light transport (progressive photon mapping) converges to
  // the closed form where the scene has one: that is the reference, with no error of its own
  // beyond float rounding.
  if (!spec.stage_knob.empty())
    if (const std::optional<tracer::Color> radiance = furnace_radiance(scene)) {
      AccuracyReference r;
      r.key = reference_key(scene, spec, options.epsilon);
      r.spec = spec;
      r.image = uniform_image(*radiance, spec.width, spec.height);
      r.floor.epsilon = options.epsilon;
      r.info = {{"key", r.key},
                {"version", kReferenceVersion},
                {"spec", to_json(spec)},
                {"floor", to_json(r.floor)},
                {"analytic", "furnace"},
                {"radiance", {(*radiance)[0], (*radiance)[1], (*radiance)[2]}}};
      r.analytic = "furnace";
      if (options.progress)
        std::fprintf(stderr, "fronts: reference %s: the furnace's closed form, radiance %.6g\n", r.key.c_str(),
                     double((*radiance)[0]));
      return r;
    }
  if (spec.stage_knob.empty() || !(options.floor_target > 0.0)) return obtain_level(scene, built, spec, options);
  // The stopping rule: level after level, each with kStageRatio times the stages of the last,
  // until the floor reaches the target or the next level (about kStageRatio times this one's
  // rendering) would pass the time limit. Each level is cached on its own, so a later run with a
  // lower target continues where this one stopped.
  const tracer::Integrator& integrator = integrators::named(spec.integrator, "reference");
  // Whether the stage knob accepts `stages` (its table's range).
  const auto accepts = [&](const json& params, long long stages) {
    json p = params;
    p[spec.stage_knob] = stages;
    try {
      integrator.params(p);
      return true;
    } catch (const std::exception&) {
      return false;
    }
  };
  ReferenceSpec level = spec;
  json levels = json::array();
  double spent_s = 0.0, rendered_now_s = 0.0;
  for (;;) {
    AccuracyReference r = obtain_level(scene, built, level, options);
    const double made_s = r.from_cache ? r.info.value("render_s", 0.0) : r.render_s;
    spent_s += made_s;
    rendered_now_s += r.render_s;
    const long long stages = stages_of(level);
    const double floor = options.floor_metric == FrontMetric::Rmse ? r.floor.rmse : r.floor.rel_mse;
    levels.push_back({{"stages", stages},
                      {"key", r.key},
                      {"floor", to_json(r.floor)},
                      {"render_s", made_s},
                      {"from_cache", r.from_cache}});
    const char* stopped_by = nullptr;
    if (floor <= options.floor_target) stopped_by = "floor";
    else if (spent_s + kStageRatio * made_s > options.time_limit_s) stopped_by = "time_limit";
    else if (!accepts(level.params, stages * kStageRatio)) stopped_by = "stage_limit";
    if (options.progress)
      std::fprintf(stderr, "fronts: reference level %s=%lld: floor %s %.4g (target %.4g)%s%s\n",
                   spec.stage_knob.c_str(), stages, metric_name(options.floor_metric), floor, options.floor_target,
                   stopped_by ? ", stopped by " : "", stopped_by ? stopped_by : "");
    if (stopped_by) {
      r.stopping = {{"target", options.floor_target},
                    {"metric", metric_name(options.floor_metric)},
                    {"time_limit_s", options.time_limit_s},
                    {"stopped_by", stopped_by},
                    {"render_s", spent_s},
                    {"levels", levels}};
      r.info["stopping"] = r.stopping;
      r.render_s = rendered_now_s;
      return r;
    }
    level.params[spec.stage_knob] = stages * kStageRatio;
  }
}

}  // namespace harness
