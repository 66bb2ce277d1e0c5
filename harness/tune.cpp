#include "harness/tune.h"

#include "harness/sweep_definition.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <set>
#include <utility>

namespace harness {
namespace {

using nlohmann::json;

bool has_knob(const std::vector<std::string>& knobs, const char* name) {
  return std::find(knobs.begin(), knobs.end(), name) != knobs.end();
}

/// Leaf sizes around `l` on a half-octave ladder.
std::vector<int> leaves_around(int l) {
  std::set<int> out;
  for (double f : {0.5, 0.7, 1.0, 1.4, 2.0}) out.insert(std::max(1, int(double(l) * f + 0.5)));
  return {out.begin(), out.end()};
}

/// The real target: builds and renders on the scene.
class RenderTarget : public TuneTarget {
 public:
  RenderTarget(const tracer::Scene& scene, const std::string& structure, const MeasureOptions& options)
      : scene_(scene), structure_(structure), options_(options), boxes_(scene.geometry.primitive_bounds()) {}

  Reference naive() override {
    contenders_.clear();
    MeasureOptions naive_options = options_;
    naive_options.keep_image = true;  // the peers' reference
    contenders_.push_back(prepare(scene_, boxes_, "naive", json::object(), naive_options, std::nullopt));
    const Measurement& m = contenders_[0].measurement;
    if (m.status != RowStatus::Ok) throw SweepError("tune: naive reference failed: " + m.reason);
    reference_ = Reference{m.image_hash, 0.0, m.rays, nullptr};
    if (contenders_[0].image) reference_.image = std::make_shared<const tracer::Image>(*contenders_[0].image);
    return reference_;
  }
  Measurement search(const json& params) override {
    return measure(scene_, boxes_, structure_, params, options_, reference_);
  }
  std::vector<bool> prepare_confirmation(const std::vector<json>& params) override {
    contenders_.resize(1);  // naive stays, prepared by naive()
    std::vector<bool> ok{contenders_[0].measurement.status == RowStatus::Ok};
    for (const json& p : params) {
      contenders_.push_back(prepare(scene_, boxes_, structure_, p, options_, reference_));
      ok.push_back(contenders_.back().measurement.status == RowStatus::Ok);
    }
    return ok;
  }
  std::optional<Sample> time(std::size_t i) override { return time_render(scene_, contenders_[i], options_); }

 private:
  const tracer::Scene& scene_;
  std::string structure_;
  MeasureOptions options_;
  std::vector<accel::Aabb> boxes_;
  Reference reference_;
  std::vector<Prepared> contenders_;  ///< Naive, then the confirmation's candidates.
};

}  // namespace

TuneResult tune_with(TuneTarget& target, const std::string& structure, const std::vector<std::string>& knobs,
                     const TuneOptions& options) {
  if (!has_knob(knobs, "max_leaf_size"))
    throw SweepError("--accel: " + structure + " has no max_leaf_size knob to tune");
  const bool with_depth = has_knob(knobs, "max_depth");
  TuneResult r;
  r.structure = structure;
  r.naive = target.naive();

  const auto params_of_point = [&](int depth, int leaf) {
    json params = options.fixed;
    params["max_leaf_size"] = leaf;
    if (with_depth) params["max_depth"] = depth;
    return params;
  };
  std::set<std::pair<int, int>> seen;
  auto evaluate = [&](int depth, int leaf, int round) {
    if (!with_depth) depth = -1;
    if (!seen.insert({depth, leaf}).second) return;
    const json params = params_of_point(depth, leaf);
    TunePoint p{depth, leaf, round, target.search(params), std::nullopt};
    if (options.progress) {
      if (p.m.status == RowStatus::Ok)
        std::fprintf(stderr, "tune: round %d: %s: %.3f ms\n", round, params.dump().c_str(), p.m.render_ms->median);
      else
        std::fprintf(stderr, "tune: round %d: %s: %s: %s\n", round, params.dump().c_str(), status_name(p.m.status),
                     p.m.reason.c_str());
    }
    r.points.push_back(std::move(p));
  };
  auto search_order = [&] {  // ok points, fastest search median first
    std::vector<std::size_t> ok;
    for (std::size_t i = 0; i < r.points.size(); ++i)
      if (r.points[i].m.status == RowStatus::Ok) ok.push_back(i);
    std::stable_sort(ok.begin(), ok.end(), [&](std::size_t a, std::size_t b) {
      return r.points[a].m.render_ms->median < r.points[b].m.render_ms->median;
    });
    return ok;
  };

  for (int d : with_depth ? options.coarse_depths : std::vector<int>{-1})
    for (int l : options.coarse_leaves) evaluate(d, l, 0);
  auto order = search_order();
  for (int round = 1; round <= options.refine_rounds && !order.empty(); ++round) {
    const std::size_t before = r.points.size(), centre_index = order.front();
    const TunePoint centre = r.points[centre_index];
    const std::vector<int> depths =
        with_depth ? std::vector<int>{centre.max_depth - 2, centre.max_depth - 1, centre.max_depth,
                                      centre.max_depth + 1, centre.max_depth + 2}
                   : std::vector<int>{-1};
    for (int d : depths)
      if (!with_depth || (d >= 0 && d <= 64))
        for (int l : leaves_around(centre.max_leaf_size)) evaluate(d, l, round);
    order = search_order();
    // Stop once a round evaluates nothing new or leaves the best where it was.
    if (r.points.size() == before || order.front() == centre_index) break;
  }
  if (order.empty()) throw SweepError("tune: no " + structure + " configuration could be built and validated");

  // The confirmation: the best of the search, and naive, timed again in interleaved rounds.
  std::vector<std::size_t> picked(order.begin(), order.begin() + std::ptrdiff_t(std::min(order.size(),
                                                                                        options.confirm_candidates)));
  std::vector<json> params;
  for (std::size_t i : picked) params.push_back(params_of_point(r.points[i].max_depth, r.points[i].max_leaf_size));
  std::vector<bool> ok = target.prepare_confirmation(params);
  r.confirm_rounds = options.confirm_rounds > 0 ? options.confirm_rounds : std::max(9, 3 * options.measure.repetitions);
  if (options.progress)
    std::fprintf(stderr, "tune: confirming the best %zu points: %d interleaved rounds with naive\n", picked.size(),
                 r.confirm_rounds);
  Rounds rounds(picked.size() + 1);
  for (int round = 0; round < r.confirm_rounds && ok[0]; ++round) {
    std::vector<std::size_t> active;
    for (std::size_t i = 0; i < ok.size(); ++i)
      if (ok[i]) active.push_back(i);
    rounds.run(active, [&](std::size_t i) {
      auto s = target.time(i);
      if (!s) ok[i] = false;
      return s;
    });
  }
  if (!ok[0]) throw SweepError("tune: naive failed while the winner was being confirmed");
  std::vector<std::size_t> contender_of;  // candidates' contender numbers, parallel to r.candidates
  for (std::size_t k = 0; k < picked.size(); ++k) {
    const std::vector<Sample> samples = rounds.samples(k + 1);
    if (!ok[k + 1] || samples.empty()) continue;
    Confirmation c;
    c.render_ms = summarize(wall_times(samples));
    c.render_ms_ci = median_interval(wall_times(samples));
    r.points[picked[k]].confirmed = c;
    r.candidates.push_back(picked[k]);
    contender_of.push_back(k + 1);
  }
  if (r.candidates.empty()) throw SweepError("tune: no candidate could be timed again to confirm it");
  std::vector<std::size_t> by_median(r.candidates.size());
  for (std::size_t k = 0; k < by_median.size(); ++k) by_median[k] = k;
  std::stable_sort(by_median.begin(), by_median.end(), [&](std::size_t a, std::size_t b) {
    return r.points[r.candidates[a]].confirmed->render_ms.median < r.points[r.candidates[b]].confirmed->render_ms.median;
  });
  const std::size_t best_k = by_median.front();
  r.best = r.candidates[best_k];
  const std::size_t best_contender = contender_of[best_k];
  r.separated = true;
  for (std::size_t k : by_median) {
    Confirmation& c = *r.points[r.candidates[k]].confirmed;
    if (k == best_k) {
      c.ratio = 1.0;
      c.ratio_ci = {1.0, 1.0};
    } else {
      const auto [own, best] = rounds.paired_wall(contender_of[k], best_contender);
      c.ratio = paired_ratio(own, best);
      c.ratio_ci = paired_ratio_interval(own, best);
    }
    if (k == best_k || c.ratio_ci.lo <= 1.0) r.tie.push_back(r.candidates[k]);
    if (k != best_k && c.ratio_ci.lo <= 1.0) r.separated = false;
    if (c.ratio_ci.lo <= 1.0 + options.flat_tolerance) r.flat.push_back(r.candidates[k]);
  }
  std::vector<std::size_t> sorted;
  for (std::size_t k : by_median) sorted.push_back(r.candidates[k]);
  r.candidates = sorted;
  const auto [naive_ms, best_ms] = rounds.paired_wall(0, best_contender);
  r.naive.render_ms = median_of(naive_ms);
  r.best_speedup = paired_ratio(naive_ms, best_ms);
  r.best_speedup_ci = paired_ratio_interval(naive_ms, best_ms);
  return r;
}

TuneResult tune(const tracer::Scene& scene, const std::string& structure, const TuneOptions& options) {
  const auto knobs = structure_knobs(structure);
  if (!knobs) throw SweepError("--accel: '" + structure + "' cannot be built here");
  RenderTarget target(scene, structure, options.measure);
  return tune_with(target, structure, *knobs, options);
}

json to_json(const TuneResult& r) {
  const auto interval = [](const Interval& i) { return json::array({i.lo, i.hi}); };
  json points = json::array();
  for (const auto& p : r.points) {
    json j = {{"max_leaf_size", p.max_leaf_size}, {"round", p.round}, {"status", status_name(p.m.status)}};
    if (p.max_depth >= 0) j["max_depth"] = p.max_depth;
    if (p.m.status != RowStatus::Ok) j["reason"] = p.m.reason;
    if (p.m.built) {
      j["params"] = p.m.params;
      j["build_ms"] = p.m.build_ms;
    }
    if (p.m.render_ms) {
      j["render_ms"] = *p.m.render_ms;
      j["nodes_per_ray"] = p.m.traversal.rays ? double(p.m.traversal.nodes_visited) / double(p.m.traversal.rays) : 0.0;
      j["prims_per_ray"] = p.m.traversal.rays ? double(p.m.traversal.prims_tested) / double(p.m.traversal.rays) : 0.0;
    }
    if (p.confirmed)
      j["confirmed"] = {{"render_ms", p.confirmed->render_ms},
                        {"render_ms_ci", interval(p.confirmed->render_ms_ci)},
                        {"ratio_to_best", p.confirmed->ratio},
                        {"ratio_to_best_ci", interval(p.confirmed->ratio_ci)}};
    points.push_back(std::move(j));
  }
  return {{"structure", r.structure},
          {"naive_render_ms", r.naive.render_ms},
          {"confirm_rounds", r.confirm_rounds},
          {"candidates", r.candidates},
          {"best", r.best},
          {"separated", r.separated},
          {"tie", r.tie},
          {"best_speedup", r.best_speedup},
          {"best_speedup_ci", interval(r.best_speedup_ci)},
          {"flat", r.flat},
          {"points", points}};
}

}  // namespace harness
