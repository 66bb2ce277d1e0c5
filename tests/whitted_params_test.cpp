// The Whitted integrator's accuracy knobs (tracer/whitted_params.h): each overrides the scene's
// setting exactly as editing the scene would, and bad knobs fail with one line naming them.

#include "tracer/render.h"
#include "tracer/whitted_params.h"

#include "scenes_gen/generators.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace {

using nlohmann::json;

tracer::RenderResult render(const tracer::Scene& scene, const json& knobs, int threads = 1) {
  const auto boxes = scene.geometry.primitive_bounds();
  const accel::AnyAccel a = accel::make_accel("naive", json::object(), boxes);
  tracer::RenderOptions options;
  options.threads = threads;
  options.width = 40;
  options.height = 30;
  return tracer::render(scene, a, options, tracer::whitted_integrator(), knobs);
}

tracer::Scene refraction() {
  scenes_gen::GenOptions gen;
  return scenes_gen::generate("refraction", gen);
}

TEST(WhittedParams, NoKnobsIsTheSceneAsWritten) {
  const tracer::Scene scene = refraction();
  const tracer::RenderResult plain = render(scene, json::object());
  const tracer::RenderResult spelled =
      render(scene, {{"max_depth", scene.render.max_depth},
                     {"min_weight", scene.render.min_weight},
                     {"spp", scene.camera.samples_per_pixel},
                     {"seed", 0}});
  EXPECT_EQ(plain.image, spelled.image);
  EXPECT_EQ(plain.stats["effective"]["max_depth"], scene.render.max_depth);
  EXPECT_EQ(plain.stats["effective"]["spp"], scene.camera.samples_per_pixel);
}

TEST(WhittedParams, KnobsOverrideTheSceneLikeEditingIt) {
  const tracer::Scene scene = refraction();
  for (int depth : {1, 2, 3, 12}) {
    tracer::Scene edited = scene;
    edited.render.max_depth = depth;
    const tracer::RenderResult by_knob = render(scene, {{"max_depth", depth}});
    const tracer::RenderResult by_scene = render(edited, json::object());
    EXPECT_EQ(by_knob.image, by_scene.image) << "max_depth " << depth;
    EXPECT_EQ(by_knob.rays, by_scene.rays) << "max_depth " << depth;
  }
  {
    tracer::Scene edited = scene;
    edited.render.min_weight = 0.2f;
    EXPECT_EQ(render(scene, {{"min_weight", 0.2}}).image, render(edited, json::object()).image);
  }
  {
    tracer::Scene edited = scene;
    edited.camera.samples_per_pixel = 4;
    const tracer::RenderResult by_knob = render(scene, {{"spp", 4}});
    EXPECT_EQ(by_knob.image, render(edited, json::object()).image);
    EXPECT_EQ(by_knob.rays.eye, 4u * 40u * 30u);
  }
  // Depth 1 traces camera and shadow rays only.
  const tracer::RenderResult d1 = render(scene, {{"max_depth", 1}});
  EXPECT_EQ(d1.rays.reflection + d1.rays.refraction, 0u);
  EXPECT_GT(render(scene, {{"max_depth", 4}}).rays.refraction, 0u);
}

TEST(WhittedParams, SeedsGiveIndependentJitterAndStayDeterministic) {
  const tracer::Scene scene = refraction();
  const json s1 = {{"spp", 4}, {"seed", 1}}, s2 = {{"spp", 4}, {"seed", 2}};
  const tracer::RenderResult a = render(scene, s1), b = render(scene, s2);
  EXPECT_NE(a.image, b.image);
  EXPECT_EQ(a.image, render(scene, s1, 3).image);  // any thread count
  EXPECT_NE(a.image, render(scene, {{"spp", 4}}).image);
  // One sample sits at the pixel centre whatever the seed.
  EXPECT_EQ(render(scene, {{"spp", 1}, {"seed", 5}}).image, render(scene, {{"spp", 1}}).image);
  // Stratification holds for every seed: one sample per stratum of the 2x2 grid.
  for (std::uint64_t seed : {0ull, 1ull, 77ull}) {
    int count[4] = {0, 0, 0, 0};
    for (int s = 0; s < 4; ++s) {
      float jx = 0, jy = 0;
      tracer::sample_offset(3, 9, s, 4, jx, jy, seed);
      ASSERT_GE(jx, 0.0f);
      ASSERT_LT(jx, 1.0f);
      count[int(jx * 2) + 2 * int(jy * 2)]++;
    }
    for (int c : count) EXPECT_EQ(c, 1) << "seed " << seed;
  }
}

TEST(WhittedParams, ParamsSpellEveryKnob) {
  const json p = tracer::whitted_integrator().params(json::object());
  EXPECT_EQ(p, json({{"max_depth", 0}, {"min_weight", -1.0}, {"spp", 0}, {"seed", 0}, {"precision", "float"}, {"triangle", "watertight"}}));
  EXPECT_EQ(tracer::whitted_integrator().params({{"max_depth", 7}})["max_depth"], 7);
}

TEST(WhittedParams, BadKnobsNameThemselves) {
  const auto message = [](const json& knobs) {
    try {
      tracer::whitted_integrator().params(knobs);
    } catch (const knobs::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({{"max_depht", 3}}).find("unknown knob 'max_depht'"), std::string::npos);
  EXPECT_NE(message({{"max_depth", 1001}}).find("'max_depth'"), std::string::npos);
  EXPECT_NE(message({{"max_depth", -1}}).find("'max_depth'"), std::string::npos);
  EXPECT_NE(message({{"max_depth", 2.5}}).find("'max_depth'"), std::string::npos);
  EXPECT_NE(message({{"min_weight", 1.5}}).find("'min_weight'"), std::string::npos);
  EXPECT_NE(message({{"min_weight", "low"}}).find("'min_weight'"), std::string::npos);
  EXPECT_NE(message({{"spp", 70000}}).find("'spp'"), std::string::npos);
  EXPECT_NE(message({{"seed", -2}}).find("'seed'"), std::string::npos);
  EXPECT_NE(message({{"precision", "half"}}).find("'precision'"), std::string::npos);
  EXPECT_NE(message(json::array()).find("JSON object"), std::string::npos);
  for (const json& bad : {json{{"max_depth", 1001}}, json{{"seed", -1}}})
    EXPECT_EQ(message(bad).find('\n'), std::string::npos);
}

}  // namespace
