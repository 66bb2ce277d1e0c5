#include "harness/fronts.h"

#include "harness/accuracy_knobs.h"
#include "harness/error_interval.h"
#include "integrators/integrators.h"
#include "harness/pareto.h"
#include "harness/sweep_results.h"

#include "tracer/render.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <stdexcept>

namespace harness {

namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string join(const std::vector<std::string>& v, const char* sep) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

/// A JSON number that may be infinite or NaN: null then (JSON has neither).
json finite_or_null(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

json error_json(const tracer::ImageError& e) {
  return {{"rmse", finite_or_null(e.rmse)},
          {"rel_mse", finite_or_null(e.rel_mse)},
          {"epsilon", e.epsilon},
          {"mean_bias", finite_or_null(e.mean_bias)},
          {"max_abs", finite_or_null(e.max_abs)},
          {"non_finite", e.non_finite}};
}

/// A metric value of a results row: null (a non-finite render) reads as infinite.
double number_or_infinity(const json& v) {
  return v.is_number() ? v.get<double>() : std::numeric_limits<double>::infinity();
}

/// The errors of a row's seeds in `metric`, the timed image's first (empty when the row has no
/// seed renders: a deterministic reference, or rows written before seed errors were recorded).
std::vector<double> seed_errors(const json& row, const char* metric) {
  std::vector<double> out;
  if (!row.contains("seed_errors") || !row["seed_errors"].contains(metric)) return out;
  for (const json& e : row["seed_errors"][metric]) out.push_back(number_or_infinity(e));
  return out;
}

/// The floor of a row's reference in the front's metric (0 when not recorded).
double row_floor(const json& row, const char* floor_key) {
  if (!row.contains("reference") || !row["reference"].contains("floor")) return 0.0;
  const json& f = row["reference"]["floor"];
  return f.contains(floor_key) && f[floor_key].is_number() ? f[floor_key].get<double>() : 0.0;
}

json bias_variance_json(const tracer::BiasVariance& bv, bool stochastic) {
  return {{"seeds", bv.seeds},
          {"stochastic", stochastic},
          {"mse", finite_or_null(bv.mse)},
          {"bias2", finite_or_null(bv.bias2)},
          {"variance", finite_or_null(bv.variance)},
          {"bias", finite_or_null(bv.bias())},
          {"noise", finite_or_null(bv.noise())},
          {"mean_bias", finite_or_null(bv.mean_bias)}};
}

}  // namespace

json to_json(const FrontsSettings& s) {
  return {{"groups", s.groups},
          {"fixed", s.fixed},
          {"reference", s.reference},
          {"metric", metric_name(s.metric)},
          {"epsilon", s.epsilon},
          {"estimator", estimator_name(s.estimator)},
          {"seeds", s.seeds}};
}

FrontsSettings fronts_settings_from_json(const json& j) {
  FrontsSettings s;
  try {
    if (!j.is_object()) throw SweepError("must be an object");
    for (const auto& [key, value] : j.items()) {
      (void)value;
      if (key != "groups" && key != "fixed" && key != "reference" && key != "metric" && key != "epsilon" &&
          key != "estimator" && key != "seeds")
        throw SweepError("/" + key + ": unknown key");
    }
    s.groups = j.at("groups").get<std::vector<std::vector<std::string>>>();
    s.fixed = j.at("fixed");
    if (!s.fixed.is_object()) throw SweepError("/fixed: must be an object");
    s.reference = j.value("reference", json::object());  // absent in files of earlier versions
    if (!s.reference.is_object()) throw SweepError("/reference: must be an object");
    const std::string metric = j.at("metric").get<std::string>();
    if (metric == "rmse") s.metric = FrontMetric::Rmse;
    else if (metric == "rel_mse") s.metric = FrontMetric::RelMse;
    else throw SweepError("/metric: must be rmse or rel_mse, got " + j["metric"].dump());
    s.epsilon = j.at("epsilon").get<double>();
    if (!(s.epsilon > 0.0) || !std::isfinite(s.epsilon)) throw SweepError("/epsilon: must be > 0");
    if (j.contains("estimator")) {  // absent in files of earlier versions: plain
      if (!j["estimator"].is_string()) throw SweepError("/estimator: must be plain or richardson");
      try {
        s.estimator = parse_estimator(j["estimator"].get<std::string>());
      } catch (const std::invalid_argument& e) {
        throw SweepError(std::string("/estimator: ") + e.what());
      }
    }
    s.seeds = j.at("seeds").get<int>();
    if (s.seeds < 1 || s.seeds > 1024) throw SweepError("/seeds: must be in [1, 1024]");
  } catch (const SweepError& e) {
    throw SweepError(std::string("/fronts") + (e.what()[0] == '/' ? "" : ": ") + e.what());
  } catch (const std::exception&) {
    throw SweepError("/fronts: needs groups (lists of knob names), fixed, metric, epsilon and seeds");
  }
  return s;
}

std::string group_name(const std::vector<std::string>& knobs) { return join(knobs, "*"); }

ReferenceSpec group_reference(const std::string& integrator, const std::vector<std::string>& group,
                              const json& fixed, int width, int height, const json& overrides,
                              ReferenceEstimator estimator) {
  ReferenceSpec spec;
  spec.width = width;
  spec.height = height;
  std::string chosen;  // the reference integrator, once a knob has named it
  for (const std::string& knob : group) {
    const AccuracyKnob* row = find_accuracy_knob(integrator, knob);
    if (!row)
      throw SweepError("integrator " + integrator + " has no accuracy knob '" + knob + "' (its accuracy knobs: " +
                       accuracy_knob_names(integrator) + ")");
    const std::string& ref_integrator = row->reference_integrator;
    if (!chosen.empty() && chosen != ref_integrator)
      throw SweepError("knobs of group " + group_name(group) + " have references from different integrators (" +
                       chosen + ", " + ref_integrator + "); vary them in separate groups");
    if (chosen.empty()) {
      chosen = ref_integrator;
      // The fixed knobs hold in the reference too, where its integrator has them.
      const json known = integrators::named(chosen, "reference").params(json::object());
      for (const auto& [k, v] : fixed.items())
        if (known.contains(k)) spec.params[k] = v;
    }
    spec.params.update(row->reference);
    spec.check.update(row->check);
    spec.stochastic = spec.stochastic || row->stochastic_reference;
  }
  spec.integrator = chosen;
  if (!overrides.empty()) {
    const json known = integrators::named(chosen, "reference").params(json::object());
    for (const auto& [k, v] : overrides.items()) {
      if (!known.contains(k))
        throw SweepError("--reference-set: the reference integrator " + chosen + " has no knob '" + k + "'");
      spec.params[k] = v;
    }
    try {
      integrators::named(chosen, "reference").params(spec.params);
    } catch (const std::exception& e) {
      throw SweepError(std::string("--reference-set: ") + e.what());
    }
  }
  if (spec.stochastic && !integrators::named(chosen, "reference").params(json::object()).contains(knobs::kSeedKnob))
    throw SweepError("reference integrator " + chosen + " has no seed knob for independent halves");
  // A reference whose error is not all noise (progressive photon mapping's shrinking radius)
  // estimates its bias from its own earlier stages.
  const tracer::Integrator& reference_integrator = integrators::named(chosen, "reference");
  if (reference_integrator.stage_knob) {
    spec.stage_knob = reference_integrator.stage_knob;
    spec.bias_order = reference_integrator.bias_order(spec.params);
    spec.estimator = estimator;
    // Its bias comes from checkpoints at N/8 (and N/64): N must divide.
    const long long stages = reference_integrator.params(spec.params).at(spec.stage_knob).get<long long>();
    const long long divisor = estimator_divisor(estimator);
    if (stages % divisor != 0)
      throw SweepError("--reference-set: a " + std::string(estimator_name(estimator)) + " " + chosen + " reference needs " +
                       spec.stage_knob + " divisible by " + std::to_string(divisor) + " (its checkpoints), got " +
                       std::to_string(stages));
  }
  return spec;
}

SweepDefinition fronts_definition(const FrontsRequest& r) {
  const tracer::Integrator& integrator = integrators::named(r.integrator, "--integrator");
  if (r.scenes.empty()) throw SweepError("SCENE: give at least one scene");
  if (r.groups.empty()) throw SweepError("--knobs: name at least one knob (accuracy knobs of " + r.integrator +
                                         ": " + accuracy_knob_names(r.integrator) + ")");
  try {
    integrator.params(r.settings.fixed);
  } catch (const std::exception& e) {
    throw SweepError(std::string("--set: ") + e.what());
  }
  std::set<std::string> studied;
  std::set<std::set<std::string>> seen_groups;
  SweepDefinition d;
  d.name = r.name;
  d.scenes = r.scenes;
  d.structures = {StructureSpec{r.structure, {}}};
  d.integrator = r.integrator;
  for (const auto& group : r.groups) {
    if (group.empty()) throw SweepError("--knobs: an empty knob group");
    const std::set<std::string> as_set(group.begin(), group.end());
    if (as_set.size() != group.size()) throw SweepError("--knobs: group " + group_name(group) + " names a knob twice");
    if (!seen_groups.insert(as_set).second) throw SweepError("--knobs: group " + group_name(group) + " is given twice");
    KnobValues axes;
    for (const std::string& knob : group) {
      const AccuracyKnob* row = find_accuracy_knob(r.integrator, knob);
      if (!row) {
        const std::string known = accuracy_knob_names(r.integrator);
        throw SweepError("--knobs: unknown knob '" + knob + "': integrator " + r.integrator +
                         (known.empty() ? " has no accuracy knobs" : " has the accuracy knobs " + known));
      }
      if (r.settings.fixed.contains(knob))
        throw SweepError("--set: knob '" + knob + "' is both varied (--knobs) and fixed (--set)");
      const auto given = r.values.find(knob);
      std::vector<json> values = given != r.values.end() ? given->second : row->values;
      if (values.empty()) throw SweepError("--values: knob '" + knob + "' has an empty range");
      for (const json& v : values) {
        try {
          integrator.params(json{{knob, v}});
        } catch (const std::exception& e) {
          throw SweepError(std::string("--values: ") + e.what());
        }
      }
      axes[knob] = values;
      studied.insert(knob);
    }
    for (const auto& [k, v] : r.settings.fixed.items()) axes[k] = {v};
    d.integrator_knobs.push_back(std::move(axes));
    group_reference(r.integrator, group, r.settings.fixed, r.width, r.height, r.settings.reference,
                    r.settings.estimator);  // throws on a bad mix
  }
  for (const auto& [knob, values] : r.values) {
    (void)values;
    if (!studied.count(knob)) throw SweepError("--values: knob '" + knob + "' is not among --knobs");
  }
  d.width = r.width;
  d.height = r.height;
  d.validate_width = r.validate_width;
  d.validate_height = r.validate_height;
  d.threads = r.threads;
  d.repetitions = r.repetitions;
  d.warmup = r.warmup;
  FrontsSettings s = r.settings;
  s.groups = r.groups;
  d.fronts = to_json(s);
  try {
    return parse_sweep_definition(to_json(d));
  } catch (const SweepError& e) {
    throw SweepError(std::string("fronts: ") + e.what());
  }
}

FrontsInspector::FrontsInspector(const SweepDefinition& definition, ReferenceOptions options)
    : integrator_(definition.integrator),
      settings_(fronts_settings_from_json(definition.fronts)),
      options_(std::move(options)),
      width_(definition.width),
      height_(definition.height) {
  options_.epsilon = settings_.epsilon;
  options_.floor_metric = settings_.metric;
  has_seed_ = integrators::named(integrator_, "integrator").params(json::object()).contains(knobs::kSeedKnob);
}

const AccuracyReference& FrontsInspector::reference(const tracer::Scene& scene, const accel::AnyAccel& built,
                                                    const std::vector<std::string>& group) {
  const auto t0 = Clock::now();
  ReferenceSpec spec =
      group_reference(integrator_, group, settings_.fixed, width_, height_, settings_.reference, settings_.estimator);
  const std::string key = reference_key(scene, spec, settings_.epsilon);
  auto it = references_.find(key);
  if (it == references_.end()) {
    AccuracyReference r = obtain_reference(scene, built, spec, options_);
    (r.from_cache ? cached_ : made_)++;
    if (options_.progress)
      std::fprintf(stderr, "fronts: reference %s %s (%s): floor RMSE %.3g (noise %.3g, truncation %.3g, bias %.3g)\n",
                   r.key.c_str(), !r.analytic.empty() ? "in closed form" : r.from_cache ? "from the cache" : "rendered", group_name(group).c_str(),
                   r.floor.rmse, r.floor.noise_rmse, r.floor.truncation_rmse, r.floor.bias_rmse);
    it = references_.emplace(key, std::move(r)).first;
  }
  reference_s_ += seconds_since(t0);
  return it->second;
}

void FrontsInspector::operator()(const tracer::Scene& scene, const accel::AnyAccel& built, const MeasureOptions& mo,
                                 const tracer::Image& image, Measurement& m) {
  // The group: the configuration's knobs less the fixed ones.
  std::set<std::string> knobs;
  for (const auto& [k, v] : mo.integrator_params.items())
    if (!settings_.fixed.contains(k)) knobs.insert(k);
  const std::vector<std::string>* group = nullptr;
  for (const auto& g : settings_.groups)
    if (std::set<std::string>(g.begin(), g.end()) == knobs) group = &g;
  if (!group) throw std::runtime_error("fronts: knobs " + mo.integrator_params.dump() + " belong to no knob group");

  const int made_before = made_;
  const AccuracyReference& ref = reference(scene, built, *group);
  if (made_ > made_before) m.spent_trace_s += ref.render_s;  // rendered for this row: rendering, not harness

  const auto t0 = Clock::now();
  double rendering_s = 0.0;
  const tracer::ImageError err = tracer::image_error(image, ref.image, settings_.epsilon);
  m.extra["front"] = group_name(*group);
  m.extra["error"] = error_json(err);
  m.extra["reference"] = {{"key", ref.key},
                          {"integrator", ref.spec.integrator},
                          {"params", ref.spec.params},
                          {"floor", to_json(ref.floor)}};
  if (!ref.stopping.is_null()) m.extra["reference"]["stopping"] = ref.stopping;
  if (!ref.analytic.empty()) m.extra["reference"]["analytic"] = ref.analytic;
  // The split into bias and variance over seeds, for knobs whose reference is itself stochastic
  // (spp, photon counts): a deterministic reference (depth 64) is rendered with the row's own
  // seed, so comparing other seeds' images with it would count their sampling noise as error.
  if (settings_.seeds >= 2 && has_seed_ && ref.spec.stochastic && !knobs.count(knobs::kSeedKnob)) {
    // The timed image's knobs (the scene's own under the requested ones) with their defaults
    // filled in: the extra seeds follow on from its seed, whatever the integrator's default.
    const tracer::Integrator& integrator = integrators::named(mo.integrator, "integrator");
    const json timed = integrator.params(scene_integrator_params(scene, mo.integrator, mo.integrator_params));
    const std::uint64_t base = timed.value(knobs::kSeedKnob, std::uint64_t(0));
    tracer::PixelMoments moments;
    moments.add(image);
    // Each seed's own error, the timed image's first: their spread is the point's seed noise
    // (harness/error_interval.h), recomputed wherever fronts are annotated (merge included).
    json seed_rmse = json::array({finite_or_null(err.rmse)});
    json seed_rel_mse = json::array({finite_or_null(err.rel_mse)});
    bool stochastic = true;
    tracer::RenderOptions ro;
    ro.threads = mo.threads;
    ro.width = mo.width;
    ro.height = mo.height;
    for (int s = 1; s < settings_.seeds; ++s) {
      json p = timed;
      p[knobs::kSeedKnob] = base + std::uint64_t(s);
      const auto r0 = Clock::now();
      const tracer::RenderResult r = tracer::render(scene, built, ro, integrator, p);
      rendering_s += seconds_since(r0);
      if (s == 1 && r.image.content_hash() == image.content_hash()) {
        stochastic = false;  // the seed changes nothing: all of the error is bias
        break;
      }
      moments.add(r.image);
      const tracer::ImageError e = tracer::image_error(r.image, ref.image, settings_.epsilon);
      seed_rmse.push_back(finite_or_null(e.rmse));
      seed_rel_mse.push_back(finite_or_null(e.rel_mse));
    }
    if (stochastic) {
      m.extra["bias_variance"] = bias_variance_json(tracer::bias_variance(moments, ref.image), true);
      m.extra["seed_errors"] = {{"rmse", seed_rmse}, {"rel_mse", seed_rel_mse}};
    } else {
      tracer::BiasVariance bv;
      bv.seeds = 1;
      bv.mse = bv.bias2 = err.mse;
      bv.mean_bias = err.mean_bias;
      m.extra["bias_variance"] = bias_variance_json(bv, false);
    }
  }
  m.spent_trace_s += rendering_s;
  error_s_ += seconds_since(t0) - rendering_s;
}

void annotate_fronts(json& results) {
  if (!results.contains("sweep") || !results["sweep"].contains("fronts")) return;
  const FrontsSettings settings = fronts_settings_from_json(results["sweep"]["fronts"]);
  const char* metric = metric_name(settings.metric);
  const char* floor_key = settings.metric == FrontMetric::Rmse ? "rmse" : "rel_mse";
  json& rows = results["rows"];
  // (scene, front) in order of first appearance -> row indices
  std::vector<std::pair<std::string, std::string>> order;
  std::map<std::pair<std::string, std::string>, std::vector<std::size_t>> members;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    json& row = rows[i];
    row.erase("on_front");
    row.erase("error_interval");
    row.erase("resolved");
    if (row.value("status", "") != "ok" || !row.contains("front") || !row.contains("error")) continue;
    const auto id = std::make_pair(row["scene"].get<std::string>(), row["front"].get<std::string>());
    if (!members.count(id)) order.push_back(id);
    members[id].push_back(i);
  }
  json fronts = json::array();
  for (const auto& id : order) {
    const std::vector<std::size_t>& idx = members[id];
    std::vector<TimeError> points;
    std::size_t unresolved = 0;
    for (std::size_t i : idx) {
      json& row = rows[i];
      const double error = number_or_infinity(row["error"][metric]);
      const ErrorInterval interval =
          error_interval(seed_spread(error, seed_errors(row, metric)), row_floor(row, floor_key), settings.metric);
      row["error_interval"] = json::array({finite_or_null(interval.lo), finite_or_null(interval.hi)});
      row["resolved"] = interval.resolved;
      unresolved += !interval.resolved;
      points.push_back({row["render_ms"]["median"].get<double>(), error, interval.resolved});
    }
    const std::vector<bool> on = pareto_front(points);
    json pareto = json::array();
    double smallest = std::numeric_limits<double>::infinity();
    for (std::size_t k : pareto_indices(points)) {
      const json& row = rows[idx[k]];
      pareto.push_back({{"key", row["key"]},
                        {"integrator_params", row.value("integrator_params", json::object())},
                        {"render_ms", points[k].time},
                        {"error", points[k].error},
                        {"resolved", points[k].resolved}});
    }
    for (std::size_t k = 0; k < idx.size(); ++k) {
      rows[idx[k]]["on_front"] = bool(on[k]);
      // A configuration equal to the reference's has error 0 and says nothing about the floor.
      if (std::isfinite(points[k].error) && points[k].error > 0.0) smallest = std::min(smallest, points[k].error);
    }
    const json& ref = rows[idx.front()]["reference"];
    const double floor = ref["floor"][floor_key].get<double>();
    json entry = {{"scene", id.first},
                  {"front", id.second},
                  {"metric", metric},
                  {"epsilon", settings.epsilon},
                  {"points", idx.size()},
                  {"pareto", pareto},
                  {"reference", ref},
                  {"floor", floor},
                  {"smallest_error", finite_or_null(smallest)},
                  {"unresolved", unresolved}};
    // How far the smallest error on the front lies above the reference's own error.
    entry["floor_ratio"] = floor > 0.0 && std::isfinite(smallest) ? json(smallest / floor) : json(nullptr);
    fronts.push_back(std::move(entry));
  }
  results["fronts"] = std::move(fronts);
}

FrontsSummary run_fronts(const SweepDefinition& definition, RunOptions options,
                         const ReferenceOptions& reference_options) {
  const auto t0 = Clock::now();
  auto inspector = std::make_shared<FrontsInspector>(definition, reference_options);
  options.inspect = [inspector](const tracer::Scene& scene, const accel::AnyAccel& built, const MeasureOptions& mo,
                                const tracer::Image& image, Measurement& m) { (*inspector)(scene, built, mo, image, m); };
  FrontsSummary out;
  out.sweep = run_sweep(definition, options);
  json results = read_results_file(options.out_path);
  annotate_fronts(results);
  write_json_atomic(options.out_path, results);
  out.wall_s = seconds_since(t0);
  out.reference_s = inspector->reference_s();
  out.references_made = inspector->references_made();
  out.references_cached = inspector->references_cached();
  const double inside = out.sweep.build_s + out.sweep.trace_s;
  out.overhead_fraction = inside > 0.0 ? (out.wall_s - inside) / inside : 0.0;
  return out;
}

}  // namespace harness
