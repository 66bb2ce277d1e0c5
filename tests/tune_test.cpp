// The tuner: a coarse grid then refinement around the best, every point validated against
// naive, the best point the fastest, and the flat region exactly the points within 5% of it.

#include "bench/sweep_definition.h"
#include "bench/tune.h"

#include "scenes_gen/generators.h"

#include <gtest/gtest.h>

#include <set>

namespace {

bench::TuneOptions small_options() {
  bench::TuneOptions o;
  o.measure.width = 24;
  o.measure.height = 18;
  o.measure.threads = 1;
  o.measure.repetitions = 1;
  o.measure.warmup = 0;
  o.coarse_depths = {2, 6, 10};
  o.coarse_leaves = {1, 4, 16};
  o.progress = false;
  return o;
}

TEST(Tune, FindsTheFastestPointAndItsFlatRegion) {
  scenes_gen::GenOptions g;
  g.count = 300;
  const tracer::Scene scene = scenes_gen::generate("random", g);
  const auto o = small_options();
  const bench::TuneResult r = bench::tune(scene, "kdtree", o);

  std::size_t coarse = 0, refined = 0;
  std::set<std::pair<int, int>> seen;
  for (const auto& p : r.points) {
    EXPECT_TRUE(seen.insert({p.max_depth, p.max_leaf_size}).second) << "point evaluated twice";
    (p.round == 0 ? coarse : refined)++;
    ASSERT_EQ(p.m.status, bench::RowStatus::Ok) << p.m.reason;
    EXPECT_EQ(p.m.image_hash, r.naive.image_hash);
    EXPECT_EQ(p.m.params["max_depth"], p.max_depth);
    EXPECT_EQ(p.m.params["max_leaf_size"], p.max_leaf_size);
  }
  EXPECT_EQ(coarse, 9u);
  EXPECT_GT(refined, 0u);

  const double best = r.points[r.best].m.render_ms->median;
  for (const auto& p : r.points) EXPECT_GE(p.m.render_ms->median, best);
  EXPECT_DOUBLE_EQ(r.best_speedup(), r.naive.render_ms / best);

  ASSERT_FALSE(r.flat.empty());
  EXPECT_EQ(r.flat.front(), r.best);
  std::size_t within = 0;
  for (const auto& p : r.points) within += p.m.render_ms->median <= best * (1.0 + o.flat_tolerance);
  EXPECT_EQ(r.flat.size(), within);

  // Refinement stays next to a best point: depth within 2 and leaf size within 2x of a centre.
  for (const auto& p : r.points)
    if (p.round > 0) {
      EXPECT_GE(p.max_depth, 0);
      EXPECT_LE(p.max_depth, 12);
    }
  const auto j = bench::to_json(r);
  EXPECT_EQ(j["points"].size(), r.points.size());
  EXPECT_EQ(j["best"], r.best);
}

TEST(Tune, RefusesStructuresWithoutALeafSizeKnob) {
  scenes_gen::GenOptions g;
  g.count = 50;
  const tracer::Scene scene = scenes_gen::generate("random", g);
  try {
    bench::tune(scene, "naive", small_options());
    ADD_FAILURE() << "naive accepted";
  } catch (const bench::SweepError& e) {
    EXPECT_EQ(std::string(e.what()), "--accel: naive has no max_leaf_size knob to tune");
  }
  EXPECT_THROW(bench::tune(scene, "kdtre", small_options()), bench::SweepError);
}

}  // namespace
