// Progressive photon mapping (photon/ppm_integrator.h), the reference of the photon knobs'
// fronts: it converges to the analytic furnace within the noise it estimates from two
// independent halves, its error falls as passes grow, it is bit-identical at any thread count,
// and bad knobs are refused with one line naming them.

#include "photon/ppm_integrator.h"

#include "scenes_gen/generators.h"
#include "scenes_gen/photon_scenes.h"

#include "accel/accel.h"
#include "tracer/image_error.h"
#include "tracer/render.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

namespace {

using nlohmann::json;

tracer::RenderResult render(const tracer::Scene& scene, const json& knobs, int threads, int w, int h,
                            std::vector<int> checkpoints = {}) {
  const accel::AnyAccel a = accel::make_accel("bvh", json::object(), scene.geometry.primitive_bounds());
  tracer::RenderOptions o;
  o.threads = threads;
  o.width = w;
  o.height = h;
  o.checkpoints = std::move(checkpoints);
  return tracer::render(scene, a, o, photon::ppm_integrator(), knobs);
}

/// An image of one colour.
tracer::Image flat(int w, int h, double value) {
  tracer::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.at(x, y) = tracer::Color(float(value));
  return img;
}

// The furnace (tests/photon_integrator_test.cpp derives it): a point light of power Phi at the
// centre of a closed diffuse sphere of radius R and albedo rho has wall radiance
// rho Phi / (4 pi^2 R^2 (1 - rho)) everywhere. The direct part comes from shadow rays; the rest is
// progressive photon mapping's. The reference is the mean of two renders with independent seeds;
// its noise, estimated from the halves as the fronts do (RMSE(A, B) / 2), must account for its
// whole error against the analytic value: no bias beyond the noise.
TEST(PpmFurnace, ConvergesToTheAnalyticValueWithinItsEstimatedNoise) {
  for (const double rho : {0.3, 0.8}) {
    SCOPED_TRACE(rho);
    const double phi = 100.0, radius = 1.0;
    const tracer::Scene scene = scenes_gen::make_furnace_scene(float(radius), float(rho), float(phi));
    const double truth = rho * phi / (4.0 * std::numbers::pi * std::numbers::pi * radius * radius * (1.0 - rho));
    std::array<double, 2> rmse{};
    std::array<double, 2> noise{};
    for (const int passes : {4, 32}) {
      const json knobs = {{"passes", passes}, {"photons_per_pass", 20000}, {"max_photon_depth", 1000}};
      json a = knobs, b = knobs;
      a["seed"] = 101;
      b["seed"] = 202;
      const tracer::Image ia = render(scene, a, 2, 16, 16).image;
      const tracer::Image ib = render(scene, b, 2, 16, 16).image;
      const std::array<tracer::Image, 2> halves = {ia, ib};
      const tracer::Image ref = tracer::mean_image(halves);
      const double noise_rmse = tracer::image_error(ia, ib).rmse / 2.0;
      const tracer::ImageError e = tracer::image_error(ref, flat(16, 16, truth));
      const int i = passes == 4 ? 0 : 1;
      rmse[std::size_t(i)] = e.rmse;
      noise[std::size_t(i)] = noise_rmse;
      // Unbiased: the error against the truth is the noise (RMSE^2 = noise^2 + bias^2; 1.5x
      // allows the estimate's own scatter and a bias of at most ~1.1 noise).
      EXPECT_LT(e.rmse, 1.5 * noise_rmse) << passes << " passes, truth " << truth;
      EXPECT_LT(std::abs(e.mean_bias), 2.0 * noise_rmse) << passes << " passes";
      // The test can fail: with 32 passes the tolerance is small next to the indirect light.
      if (passes == 32) {
        EXPECT_LT(1.5 * noise_rmse, 0.08 * truth * rho);
      }
      std::printf("furnace rho %.1f, %d passes: rmse %.5g, noise %.5g, mean bias %.4g, truth %.5g\n", rho, passes,
                  e.rmse, noise_rmse, e.mean_bias, truth);
    }
    // 8x the photons: the MSE falls about as N^-2/3, the RMSE by about 8^(1/3) = 2.
    EXPECT_LT(rmse[1], 0.75 * rmse[0]);
    EXPECT_LT(noise[1], 0.75 * noise[0]);
  }
}

// max_paths cuts a pass short of photons_per_pass: every map of every pass (and the pilot pass)
// then emits exactly max_paths paths, and the estimate stays unbiased because each photon carries
// the light's power over the paths emitted.
TEST(PpmFurnace, APassCutShortByMaxPathsStaysUnbiased) {
  const double rho = 0.8, phi = 100.0;
  const tracer::Scene scene = scenes_gen::make_furnace_scene(1.0f, float(rho), float(phi));
  const double truth = rho * phi / (4.0 * std::numbers::pi * std::numbers::pi * (1.0 - rho));
  const int passes = 16;
  const std::uint64_t cap = 3000;  // about 4 photons stored per path at rho 0.8: 12,000 < 20,000 asked
  json a = {{"passes", passes}, {"photons_per_pass", 20000}, {"max_paths", cap}, {"max_photon_depth", 1000},
            {"seed", 11}};
  json b = a;
  b["seed"] = 12;
  const tracer::RenderResult ra = render(scene, a, 2, 16, 16);
  const tracer::RenderResult rb = render(scene, b, 2, 16, 16);
  // The furnace needs only the global map: passes + the pilot pass, cap paths each.
  EXPECT_EQ(ra.stats["photon_paths"].get<std::uint64_t>(), std::uint64_t(passes + 1) * cap);
  EXPECT_LT(ra.stats["photons_stored"].get<std::uint64_t>(), std::uint64_t(passes + 1) * 20000);
  const std::array<tracer::Image, 2> halves = {ra.image, rb.image};
  const double noise_rmse = tracer::image_error(ra.image, rb.image).rmse / 2.0;
  const tracer::ImageError e = tracer::image_error(tracer::mean_image(halves), flat(16, 16, truth));
  EXPECT_LT(e.rmse, 1.5 * noise_rmse) << "truth " << truth;
  EXPECT_LT(std::abs(e.mean_bias), 2.0 * noise_rmse);
  std::printf("furnace rho 0.8, %d passes of %llu paths: rmse %.5g, noise %.5g, mean bias %.4g, truth %.5g\n", passes,
              (unsigned long long)cap, e.rmse, noise_rmse, e.mean_bias, truth);
}

TEST(PpmDeterminism, BitIdenticalAtAnyThreadCount) {
  const tracer::Scene scene = scenes_gen::generate("cornell", {});
  const json knobs = {{"passes", 3}, {"photons_per_pass", 5000}};
  const tracer::RenderResult one = render(scene, knobs, 1, 40, 30);
  const tracer::RenderResult three = render(scene, knobs, 3, 40, 30);
  EXPECT_EQ(one.image.pixels(), three.image.pixels());
  EXPECT_EQ(one.stats["photons_stored"], three.stats["photons_stored"]);
  EXPECT_EQ(one.stats["visible_points"], three.stats["visible_points"]);
  // Another seed gives another image (the seed reaches every pass).
  const tracer::RenderResult other = render(scene, {{"passes", 3}, {"photons_per_pass", 5000}, {"seed", 7}}, 2, 40, 30);
  EXPECT_NE(one.image.pixels(), other.image.pixels());
}

// The earlier stages a reference estimates its bias from (harness/reference_floor.h) are the
// render stopped there: bit for bit, at any thread count, and they cost no second render.
TEST(PpmCheckpoints, AreTheRendersStoppedThere) {
  const tracer::Scene scene = scenes_gen::generate("glass_caustic", {});
  const json knobs = {{"passes", 8}, {"photons_per_pass", 3000}};
  const tracer::RenderResult full = render(scene, knobs, 2, 32, 24, {4, 1, 8, 0, 4, 12});
  // 8, 0 and 12 are not below the render's passes; 4 is asked for twice.
  ASSERT_EQ(full.checkpoints.size(), 2u);
  EXPECT_EQ(full.checkpoints[0].first, 1);
  EXPECT_EQ(full.checkpoints[1].first, 4);
  for (const auto& [passes, image] : full.checkpoints) {
    json stopped = knobs;
    stopped["passes"] = passes;
    EXPECT_EQ(image.pixels(), render(scene, stopped, 1, 32, 24).image.pixels()) << passes << " passes";
  }
  EXPECT_EQ(full.image.pixels(), render(scene, knobs, 1, 32, 24).image.pixels());
  EXPECT_NE(full.checkpoints[1].second.pixels(), full.image.pixels());
  EXPECT_NEAR(photon::ppm_integrator().bias_order(json::object()), 1.0 / 3.0, 1e-6);
  EXPECT_STREQ(photon::ppm_integrator().stage_knob, "passes");
}

TEST(PpmKnobs, BadKnobsAreOneLineNamingTheKnob) {
  const auto message = [](const json& j) -> std::string {
    try {
      (void)photon::PpmParams::knobs().from_json(j);
    } catch (const knobs::ConfigError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message({{"passes", 0}}).find("'passes'"), std::string::npos);
  EXPECT_NE(message({{"alpha", 1.5}}).find("'alpha'"), std::string::npos);
  EXPECT_NE(message({{"initial_radius", -1}}).find("'initial_radius'"), std::string::npos);
  EXPECT_NE(message({{"initial_photons", 0}}).find("'initial_photons'"), std::string::npos);
  EXPECT_NE(message({{"photons", 10}}).find("photons"), std::string::npos);
  EXPECT_NE(message({{"max_paths", -1}}).find("'max_paths'"), std::string::npos);
  EXPECT_NE(message({{"max_paths", 1LL << 41}}).find("'max_paths'"), std::string::npos);
  EXPECT_EQ(message(json::object()), "");
  for (const json& bad : {json{{"passes", 0}}, json{{"alpha", "x"}}})
    EXPECT_EQ(message(bad).find('\n'), std::string::npos);
  // Defaults round-trip through JSON.
  const photon::PpmParams p = json(photon::PpmParams{}).get<photon::PpmParams>();
  EXPECT_EQ(json(p), json(photon::PpmParams{}));
}

}  // namespace
