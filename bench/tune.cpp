#include "tune.h"

#include "sweep_definition.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <set>
#include <utility>

namespace bench {
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

}  // namespace

TuneResult tune(const tracer::Scene& scene, const std::string& structure, const TuneOptions& options) {
  const auto knobs = structure_knobs(structure);
  if (!knobs) throw SweepError("--accel: '" + structure + "' cannot be built here");
  if (!has_knob(*knobs, "max_leaf_size"))
    throw SweepError("--accel: " + structure + " has no max_leaf_size knob to tune");
  const bool with_depth = has_knob(*knobs, "max_depth");

  const std::vector<accel::Aabb> boxes = scene.geometry.primitive_bounds();
  TuneResult r;
  r.structure = structure;
  const Measurement naive = measure(scene, boxes, "naive", json::object(), options.measure, std::nullopt);
  if (naive.status != RowStatus::Ok) throw SweepError("tune: naive reference failed: " + naive.reason);
  r.naive = Reference{naive.image_hash, naive.render_ms->median, naive.rays};
  if (options.progress)
    std::fprintf(stderr, "tune: naive reference: %.2f ms\n", r.naive.render_ms);

  std::set<std::pair<int, int>> seen;
  auto evaluate = [&](int depth, int leaf, int round) {
    if (!with_depth) depth = -1;
    if (!seen.insert({depth, leaf}).second) return;
    json params = options.fixed;
    params["max_leaf_size"] = leaf;
    if (with_depth) params["max_depth"] = depth;
    TunePoint p{depth, leaf, round, measure(scene, boxes, structure, params, options.measure, r.naive)};
    if (options.progress) {
      if (p.m.status == RowStatus::Ok)
        std::fprintf(stderr, "tune: round %d: %s: %.3f ms, %.1fx naive\n", round, params.dump().c_str(),
                     p.m.render_ms->median, r.naive.render_ms / p.m.render_ms->median);
      else
        std::fprintf(stderr, "tune: round %d: %s: %s: %s\n", round, params.dump().c_str(), status_name(p.m.status),
                     p.m.reason.c_str());
    }
    r.points.push_back(std::move(p));
  };
  auto find_best = [&]() -> std::optional<std::size_t> {
    std::optional<std::size_t> best;
    for (std::size_t i = 0; i < r.points.size(); ++i) {
      const auto& m = r.points[i].m;
      if (m.status == RowStatus::Ok && (!best || m.render_ms->median < r.points[*best].m.render_ms->median))
        best = i;
    }
    return best;
  };

  for (int d : with_depth ? options.coarse_depths : std::vector<int>{-1})
    for (int l : options.coarse_leaves) evaluate(d, l, 0);
  auto best = find_best();
  for (int round = 1; round <= options.refine_rounds && best; ++round) {
    const std::size_t before = r.points.size();
    const TunePoint centre = r.points[*best];
    const std::vector<int> depths =
        with_depth ? std::vector<int>{centre.max_depth - 2, centre.max_depth - 1, centre.max_depth,
                                      centre.max_depth + 1, centre.max_depth + 2}
                   : std::vector<int>{-1};
    for (int d : depths)
      if (!with_depth || (d >= 0 && d <= 64))
        for (int l : leaves_around(centre.max_leaf_size)) evaluate(d, l, round);
    const auto next = find_best();
    // Stop once a round evaluates nothing new or leaves the best where it was.
    if (r.points.size() == before || next == best) break;
    best = next;
  }
  if (!best) throw SweepError("tune: no " + structure + " configuration could be built and validated");
  r.best = *best;
  const double limit = r.points[r.best].m.render_ms->median * (1.0 + options.flat_tolerance);
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    const auto& m = r.points[i].m;
    if (m.status == RowStatus::Ok && m.render_ms->median <= limit) r.flat.push_back(i);
  }
  std::sort(r.flat.begin(), r.flat.end(), [&](std::size_t a, std::size_t b) {
    return r.points[a].m.render_ms->median < r.points[b].m.render_ms->median;
  });
  return r;
}

json to_json(const TuneResult& r) {
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
      j["speedup"] = r.naive.render_ms / p.m.render_ms->median;
      j["nodes_per_ray"] = p.m.traversal.rays ? double(p.m.traversal.nodes_visited) / double(p.m.traversal.rays) : 0.0;
    }
    points.push_back(std::move(j));
  }
  json flat = json::array();
  for (std::size_t i : r.flat) flat.push_back(i);
  return {{"structure", r.structure},
          {"naive_render_ms", r.naive.render_ms},
          {"best", r.best},
          {"best_speedup", r.best_speedup()},
          {"flat", flat},
          {"points", points}};
}

}  // namespace bench
