// The tuner: a coarse grid then refinement around the best, every point validated against
// naive; then the best candidates timed again, interleaved with naive, and a winner named only
// when its interval separates it from the rest. Synthetic timings with noise check the rule: a
// single lucky sample never wins, a flat optimum is a tie, a clear winner is named.

#include "harness/sweep_definition.h"
#include "harness/tune.h"

#include "scenes_gen/generators.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>

namespace {

using nlohmann::json;

harness::TuneOptions small_options() {
  harness::TuneOptions o;
  o.measure.width = 24;
  o.measure.height = 18;
  o.measure.threads = 1;
  o.measure.repetitions = 1;
  o.measure.warmup = 0;
  o.coarse_depths = {2, 6, 10};
  o.coarse_leaves = {1, 4, 16};
  o.confirm_candidates = 3;
  o.confirm_rounds = 3;
  o.progress = false;
  return o;
}

TEST(Tune, SearchesValidatesAndConfirmsOnARealScene) {
  scenes_gen::GenOptions g;
  g.count = 300;
  const tracer::Scene scene = scenes_gen::generate("random", g);
  const auto o = small_options();
  const harness::TuneResult r = harness::tune(scene, "kdtree", o);

  std::size_t coarse = 0, refined = 0;
  std::set<std::pair<int, int>> seen;
  for (const auto& p : r.points) {
    EXPECT_TRUE(seen.insert({p.max_depth, p.max_leaf_size}).second) << "point evaluated twice";
    (p.round == 0 ? coarse : refined)++;
    ASSERT_EQ(p.m.status, harness::RowStatus::Ok) << p.m.reason;
    EXPECT_EQ(p.m.image_hash, r.naive.image_hash);
    EXPECT_EQ(p.m.params["max_depth"], p.max_depth);
    EXPECT_EQ(p.m.params["max_leaf_size"], p.max_leaf_size);
  }
  EXPECT_EQ(coarse, 9u);
  EXPECT_GT(refined, 0u);

  // The confirmation: three candidates, each timed in every round, the fastest first.
  ASSERT_EQ(r.candidates.size(), 3u);
  EXPECT_EQ(r.candidates.front(), r.best);
  double last = 0.0;
  for (std::size_t i : r.candidates) {
    ASSERT_TRUE(r.points[i].confirmed.has_value());
    const auto& c = *r.points[i].confirmed;
    EXPECT_EQ(c.render_ms.samples.size(), 3u);
    EXPECT_GE(c.render_ms.median, last);
    last = c.render_ms.median;
    EXPECT_LE(c.ratio_ci.lo, c.ratio);
    EXPECT_GE(c.ratio_ci.hi, c.ratio);
  }
  EXPECT_EQ(r.points[r.best].confirmed->ratio, 1.0);
  EXPECT_EQ(r.tie.front(), r.best);
  EXPECT_EQ(r.separated, r.tie.size() == 1);
  EXPECT_FALSE(r.flat.empty());
  EXPECT_GT(r.naive.render_ms, 0.0);
  EXPECT_LE(r.best_speedup_ci.lo, r.best_speedup);
  EXPECT_GE(r.best_speedup_ci.hi, r.best_speedup);

  const auto j = harness::to_json(r);
  EXPECT_EQ(j["points"].size(), r.points.size());
  EXPECT_EQ(j["best"], r.best);
  EXPECT_TRUE(j["points"][r.best].contains("confirmed"));
}

TEST(Tune, RefusesStructuresWithoutALeafSizeKnob) {
  scenes_gen::GenOptions g;
  g.count = 50;
  const tracer::Scene scene = scenes_gen::generate("random", g);
  try {
    harness::tune(scene, "naive", small_options());
    ADD_FAILURE() << "naive accepted";
  } catch (const harness::SweepError& e) {
    EXPECT_EQ(std::string(e.what()), "--accel: naive has no max_leaf_size knob to tune");
  }
  EXPECT_THROW(harness::tune(scene, "kdtre", small_options()), harness::SweepError);
}

/// Timings of a made-up structure: each point's true time, with multiplicative noise (and a
/// drift shared by every render of a round), and optionally one lucky search sample.
class SyntheticTarget : public harness::TuneTarget {
 public:
  using TrueTime = std::function<double(int depth, int leaf)>;
  SyntheticTarget(TrueTime truth, double noise, std::pair<int, int> lucky = {-100, -100})
      : truth_(std::move(truth)), noise_(noise), lucky_(lucky), rng_(42) {}

  harness::Reference naive() override { return {1, 0.0, {}, nullptr}; }

  harness::Measurement search(const json& params) override {
    const int d = params.value("max_depth", -1), l = params["max_leaf_size"];
    harness::Measurement m;
    m.built = true;
    m.params = params;
    m.image_hash = 1;
    std::vector<double> samples;
    for (int i = 0; i < 3; ++i) samples.push_back(truth_(d, l) * jitter());
    // The lucky point's search: its samples fell at a quarter of its true time (a quiet moment).
    if (std::make_pair(d, l) == lucky_)
      for (double& s : samples) s = truth_(d, l) / 4.0;
    m.render_ms = harness::summarize(samples);
    return m;
  }

  std::vector<bool> prepare_confirmation(const std::vector<json>& params) override {
    confirm_ = params;
    return std::vector<bool>(params.size() + 1, true);
  }

  std::optional<harness::Sample> time(std::size_t i) override {
    // Every contender is timed once per round: a new round begins every n + 1 calls, with a
    // drift of the machine that all of that round's renders share.
    if (calls_++ % (confirm_.size() + 1) == 0) drift_ = 1.0 + 0.3 * std::sin(double(rounds_++));
    const double t = i == 0 ? 1000.0 : truth_(confirm_[i - 1].value("max_depth", -1), confirm_[i - 1]["max_leaf_size"]);
    const double ms = t * drift_ * jitter();
    return harness::Sample{ms, ms};
  }

 private:
  double jitter() { return std::exp(noise_ * std::normal_distribution<double>()(rng_)); }
  TrueTime truth_;
  double noise_;
  std::pair<int, int> lucky_;
  std::mt19937_64 rng_;
  std::vector<json> confirm_;
  std::size_t calls_ = 0;
  int rounds_ = 0;
  double drift_ = 1.0;
};

harness::TuneOptions synthetic_options() {
  harness::TuneOptions o;
  o.measure.repetitions = 3;
  o.confirm_candidates = 6;
  o.confirm_rounds = 15;
  o.progress = false;
  return o;
}

const std::vector<std::string> kKnobs = {"max_depth", "max_leaf_size", "placement"};

TEST(TuneSynthetic, ASingleLuckySampleNeverWins) {
  // A bowl with its true optimum at depth 14, leaf 8 (40 ms); depth 5, leaf 32 is much slower
  // but its search measurement was one lucky moment at a quarter of its time.
  const auto truth = [](int d, int l) {
    return 40.0 * (1.0 + 0.02 * (d - 14) * (d - 14) + 0.05 * std::pow(std::log2(double(l) / 8.0), 2.0));
  };
  ASSERT_GT(truth(5, 32), 1.3 * truth(14, 8));
  ASSERT_LT(truth(5, 32) / 4.0, 0.9 * truth(14, 8));
  SyntheticTarget target(truth, 0.03, {5, 32});
  const harness::TuneResult r = harness::tune_with(target, "kdtree", kKnobs, synthetic_options());
  // The search was fooled: the lucky point had the fastest search median...
  std::size_t lucky = r.points.size();
  for (std::size_t i = 0; i < r.points.size(); ++i)
    if (r.points[i].max_depth == 5 && r.points[i].max_leaf_size == 32) lucky = i;
  ASSERT_LT(lucky, r.points.size());
  for (const auto& p : r.points) EXPECT_GE(p.m.render_ms->median, r.points[lucky].m.render_ms->median);
  // ...but the confirmation times it again: it neither wins nor ties with the winner.
  ASSERT_TRUE(r.points[lucky].confirmed.has_value());
  EXPECT_NE(r.best, lucky);
  EXPECT_EQ(std::count(r.tie.begin(), r.tie.end(), lucky), 0);
  EXPECT_GT(r.points[lucky].confirmed->ratio_ci.lo, 1.0);
  EXPECT_NEAR(r.points[r.best].confirmed->render_ms.median, truth(r.points[r.best].max_depth,
                                                                   r.points[r.best].max_leaf_size),
              0.35 * 40.0);  // within the drift of the synthetic machine
}

TEST(TuneSynthetic, AFlatOptimumIsATieAndAClearOneAWinner) {
  // Flat: every depth from 10 to 20 with leaf 4-16 takes the same 50 ms.
  const auto flat = [](int d, int l) { return (d >= 10 && d <= 20 && l >= 4 && l <= 16) ? 50.0 : 80.0; };
  SyntheticTarget flat_target(flat, 0.05);
  const harness::TuneResult f = harness::tune_with(flat_target, "kdtree", kKnobs, synthetic_options());
  EXPECT_FALSE(f.separated);
  EXPECT_GE(f.tie.size(), 2u);
  for (std::size_t i : f.tie) EXPECT_EQ(flat(f.points[i].max_depth, f.points[i].max_leaf_size), 50.0);
  EXPECT_GE(f.flat.size(), f.tie.size());

  // Clear: one point is 20% faster than every other; low noise.
  const auto sharp = [](int d, int l) { return (d == 14 && l == 8) ? 40.0 : 50.0 + d + l; };
  SyntheticTarget sharp_target(sharp, 0.01);
  const harness::TuneResult s = harness::tune_with(sharp_target, "kdtree", kKnobs, synthetic_options());
  EXPECT_TRUE(s.separated);
  ASSERT_EQ(s.tie.size(), 1u);
  EXPECT_EQ(s.points[s.best].max_depth, 14);
  EXPECT_EQ(s.points[s.best].max_leaf_size, 8);
  EXPECT_NEAR(s.best_speedup, 1000.0 / 40.0, 1.0);
  EXPECT_LE(s.best_speedup_ci.lo, s.best_speedup);
  EXPECT_GE(s.best_speedup_ci.hi, s.best_speedup);
}

}  // namespace
