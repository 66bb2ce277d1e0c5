// The photon-mapping integrator (photon/photon_integrator.h) and its photon tracing
// (photon/photon_tracing.h): the analytic furnace, determinism at any thread count and across
// runs, every structure equal to naive, modelling only the maps a scene needs, and bad knobs.

#include "photon/packed_power.h"
#include "photon/photon_integrator.h"

#include "scenes_gen/generators.h"
#include "scenes_gen/materials.h"
#include "scenes_gen/photon_scenes.h"

#include "tracer/render.h"

#include "structure_configs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <string>

namespace {

using nlohmann::json;
using tracer::Color;
using tracer::Vec3;

constexpr double kPi = std::numbers::pi;

tracer::RenderResult render(const tracer::Scene& scene, const test_support::StructureConfig& structure,
                            const json& knobs, int threads = 2, int w = 32, int h = 32) {
  const accel::AnyAccel a = structure.build(scene.geometry.primitive_bounds());
  tracer::RenderOptions o;
  o.threads = threads;
  o.width = w;
  o.height = h;
  return tracer::render(scene, a, o, photon::photon_integrator(), knobs);
}

photon::PhotonMaps maps_of(const tracer::Scene& scene, const test_support::StructureConfig& structure,
                           const json& knobs, int threads) {
  const accel::AnyAccel a = structure.build(scene.geometry.primitive_bounds());
  tracer::RenderOptions o;
  o.threads = threads;
  const photon::PhotonParams p = knobs.get<photon::PhotonParams>();
  return photon::make_photon_maps(scene, a, p, o, /*keep_photons=*/true);
}

bool same_photons(const std::vector<photon::Photon>& a, const std::vector<photon::Photon>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(photon::Photon)) == 0);
}

// ---------------------------------------------------------------------------------------------
// The furnace: a point light of power Phi at the centre of a closed diffuse sphere of radius R
// and albedo rho. Direct irradiance on the wall is E_d = Phi / (4 pi R^2). Every wall point sees
// the whole inside, so the irradiance from the walls equals their radiosity rho E, and
// E = E_d + rho E gives E = E_d / (1 - rho). The wall radiance is rho E / pi:
//   direct alone  L_d = rho Phi / (4 pi^2 R^2),
//   full          L   = rho Phi / (4 pi^2 R^2 (1 - rho)).
// The integrator computes L_d by shadow rays (exact) and the rest, L_i = L - L_d, from the global
// map. Its estimate of L_i, with the box filter over the k nearest photons:
//   - bias: the k photons are the nearest of a uniform field, so the expected box estimate is
//     k/(k-1) of the truth (docs/photon-kdtree.md derives it for a plane; on a sphere the points
//     within chord distance r form a cap of area exactly pi r^2, Archimedes, so it holds
//     unchanged). Each photon's power is stored rounded (packed_power.h) by the known factor
//     q = decode(encode(Phi/n))/(Phi/n). Expected: L_d + L_i q k/(k-1).
//   - noise: the map holds N photons from n paths; each path stores a geometric number of
//     photons G (P(G >= m) = rho^m, mean rho/(1-rho), variance rho/(1-rho)^2), so the flux
//     N Phi/n carries a relative standard deviation sqrt(var G / (mean G)^2 / n) =
//     sqrt(1/(rho n)) = sqrt(1/((1-rho) N)). The image (90 degrees square) averages the density
//     over a sixth of the sphere, about N/6 photons, adding sqrt(6/N) for where they fell.
//     sigma = L_i sqrt(1/((1-rho) N) + 6/N); the test allows 4 sigma (2 sigma per term summed
//     linearly would be tighter; they are not independent).
TEST(PhotonFurnace, DirectLightAloneIsTheSinglebounceValue) {
  for (const float rho : {0.3f, 0.5f, 0.8f}) {
    const tracer::Scene scene = scenes_gen::make_furnace_scene(1.0f, rho, 100.0f);
    const auto boxes = scene.geometry.primitive_bounds();
    tracer::RenderOptions o;
    o.width = o.height = 16;
    const tracer::RenderResult r = tracer::render(
        scene, accel::make_accel("naive", json::object(), boxes), o, tracer::whitted_integrator());
    const double l_direct = rho * 100.0 / (4.0 * kPi * kPi);
    EXPECT_NEAR(r.image.mean(), l_direct, l_direct * 1e-5) << rho;
  }
}

TEST(PhotonFurnace, ReachesTheFullSolution) {
  const int n_photons = 100000, k = 100;
  for (const double rho : {0.3, 0.5, 0.8}) {
    SCOPED_TRACE(rho);
    const double phi = 100.0, radius = 1.0;
    const tracer::Scene scene = scenes_gen::make_furnace_scene(float(radius), float(rho), float(phi));
    const tracer::RenderResult r =
        render(scene, "bvh",
               {{"global_photons", n_photons}, {"k", k}, {"filter", "box"}, {"seed", 11},
                {"max_photon_depth", 1000}},
               2, 24, 24);
    const json& global = r.stats["maps"]["global"];
    ASSERT_EQ(global["stored"], n_photons);
    EXPECT_TRUE(r.stats["maps"]["caustic"].contains("skipped"));
    const double emitted = global["emitted"].get<double>();
    const float per_photon = float(phi / emitted);
    const double q = double(photon::unpack_power(photon::pack_power(Color(per_photon))).x) / per_photon;

    const double l_direct = rho * phi / (4.0 * kPi * kPi * radius * radius);
    const double l_full = l_direct / (1.0 - rho);
    const double l_indirect = l_full - l_direct;
    const double expected = l_direct + l_indirect * q * k / (k - 1.0);
    const double sigma =
        l_indirect * std::sqrt(1.0 / ((1.0 - rho) * n_photons) + 6.0 / n_photons);
    const double mean = r.image.mean();
    EXPECT_NEAR(mean, expected, 4.0 * sigma) << "full " << l_full << ", sigma " << sigma;
    // The tolerance is well below the indirect light itself: storing the first diffuse hit, or
    // losing a bounce, would fail.
    EXPECT_LT(4.0 * sigma, 0.1 * l_indirect);
    // Per-pixel estimates scatter about the mean, but none is wild.
    for (const Color& c : r.image.pixels()) EXPECT_NEAR(c.x, l_full, 0.35 * l_full);
  }
}

TEST(PhotonFurnace, FinalGatheringReachesTheFullSolutionToo) {
  // With final gathering, E_indirect = pi/M sum of M gather rays' radiance, each reading
  // direct + global map at the wall it meets: expected rho (E_d + E_g q k/(k-1)) / pi * ... the
  // same expectation as above; the gather adds noise of its own (cosine rays over a uniform
  // field see the same radiance, so little), and the per-pixel estimates average more photons.
  const double rho = 0.5, phi = 100.0;
  const int n_photons = 50000, k = 100;
  const tracer::Scene scene = scenes_gen::make_furnace_scene(1.0f, float(rho), float(phi));
  const tracer::RenderResult r =
      render(scene, "bvh",
             {{"global_photons", n_photons}, {"k", k}, {"filter", "box"},
              {"final_gather_rays", 16}, {"max_photon_depth", 1000}},
             2, 12, 12);
  const double emitted = r.stats["maps"]["global"]["emitted"].get<double>();
  const float per_photon = float(phi / emitted);
  const double q = double(photon::unpack_power(photon::pack_power(Color(per_photon))).x) / per_photon;
  const double l_direct = rho * phi / (4.0 * kPi * kPi);
  const double l_indirect = l_direct / (1.0 - rho) - l_direct;
  const double expected = l_direct + l_indirect * q * k / (k - 1.0);
  // Gather rays reach the whole sphere: the average is over all N photons, noise
  // sqrt(1/((1-rho) N) + 1/N).
  const double sigma = l_indirect * std::sqrt(1.0 / ((1.0 - rho) * n_photons) + 1.0 / n_photons);
  EXPECT_NEAR(r.image.mean(), expected, 4.0 * sigma);
  EXPECT_EQ(r.rays.gather, 12u * 12u * 16u);
}

// ---------------------------------------------------------------------------------------------

json small_cornell_knobs() {
  return {{"global_photons", 20000}, {"caustic_photons", 20000}, {"k", 40},
          {"final_gather_rays", 4}};
}

TEST(PhotonDeterminism, MapsAndImagesAreBitIdenticalAtAnyThreadCountAndAcrossRuns) {
  const tracer::Scene scene = scenes_gen::generate("cornell", {});
  const photon::PhotonMaps one = maps_of(scene, "bvh", small_cornell_knobs(), 1);
  ASSERT_EQ(one.global_pass.photons.size(), 20000u);
  ASSERT_EQ(one.caustic_pass.photons.size(), 20000u);
  const tracer::RenderResult image_one = render(scene, "bvh", small_cornell_knobs(), 1);
  for (int threads : {2, 7, 7}) {
    SCOPED_TRACE(threads);
    const photon::PhotonMaps many = maps_of(scene, "bvh", small_cornell_knobs(), threads);
    EXPECT_TRUE(same_photons(many.global_pass.photons, one.global_pass.photons));
    EXPECT_TRUE(same_photons(many.caustic_pass.photons, one.caustic_pass.photons));
    EXPECT_EQ(many.global_pass.emitted, one.global_pass.emitted);
    const tracer::RenderResult image = render(scene, "bvh", small_cornell_knobs(), threads);
    EXPECT_EQ(image.image.content_hash(), image_one.image.content_hash());
    EXPECT_EQ(image.rays, image_one.rays);
  }
  // Another seed gives other photons.
  json other = small_cornell_knobs();
  other["seed"] = 2;
  EXPECT_FALSE(same_photons(maps_of(scene, "bvh", other, 2).global_pass.photons,
                            one.global_pass.photons));
}

TEST(PhotonStructures, EveryStructureGivesNaivesMapsAndImage) {
  const tracer::Scene scene = scenes_gen::generate("cornell", {});
  json knobs = small_cornell_knobs();
  knobs["global_photons"] = 5000;
  knobs["caustic_photons"] = 5000;
  const photon::PhotonMaps ref = maps_of(scene, "naive", knobs, 2);
  const tracer::RenderResult ref_image = render(scene, "naive", knobs, 2, 24, 24);
  for (const test_support::StructureConfig& structure : test_support::structures_at_every_isa()) {
    SCOPED_TRACE(structure.label());
    const photon::PhotonMaps m = maps_of(scene, structure, knobs, 2);
    EXPECT_TRUE(same_photons(m.global_pass.photons, ref.global_pass.photons));
    EXPECT_TRUE(same_photons(m.caustic_pass.photons, ref.caustic_pass.photons));
    const tracer::RenderResult image = render(scene, structure, knobs, 2, 24, 24);
    EXPECT_EQ(image.image.content_hash(), ref_image.image.content_hash());
    EXPECT_EQ(image.rays, ref_image.rays);
  }
}

TEST(PhotonStructures, TreeVariantsAndCacheDistancesLeaveTheImageBitIdentical) {
  const tracer::Scene scene = scenes_gen::generate("cornell", {});
  json knobs = small_cornell_knobs();
  const auto ref = render(scene, "bvh", knobs, 2, 24, 24).image.content_hash();
  for (const char* tree : {"sliding_midpoint", "median_buckets", "brute_force"}) {
    knobs["photon_tree"] = tree;
    EXPECT_EQ(render(scene, "bvh", knobs, 2, 24, 24).image.content_hash(), ref) << tree;
  }
  knobs["photon_tree"] = "balanced";
  knobs["cache_distances"] = false;
  EXPECT_EQ(render(scene, "bvh", knobs, 2, 24, 24).image.content_hash(), ref);
}

// ---------------------------------------------------------------------------------------------

TEST(PhotonMaps, CausticPhotonsLieWhereTheGlassFocusesAndGlobalOnesSkipTheFirstHit) {
  const tracer::Scene scene = scenes_gen::generate("glass_caustic", {});
  const photon::PhotonMaps m =
      maps_of(scene, "bvh", {{"global_photons", 5000}, {"caustic_photons", 5000}}, 2);
  // Caustic photons: only on the floor (y = 0) or the wall behind (z = -4), after the glass.
  for (const photon::Photon& p : m.caustic_pass.photons) {
    const bool floor = std::abs(p.position.y) < 1e-4f, wall = std::abs(p.position.z + 4.0f) < 1e-4f;
    ASSERT_TRUE(floor || wall) << p.position.x << " " << p.position.y << " " << p.position.z;
  }
  // A single floor plane under a light: every photon's first hit is the floor and its bounce
  // escapes, so the global map gets nothing; the pass stops at its cap.
  tracer::Scene plane;
  plane.materials = {scenes_gen::diffuse("floor", Color(0.8f))};
  plane.geometry.planes.push_back({Vec3(0, 1, 0), 0.0f, 0});
  plane.lights = {scenes_gen::point_light({0, 2, 0}, 100.0f)};
  plane.geometry.finalize();
  const photon::PhotonMaps p = maps_of(plane, "naive", {{"global_photons", 10}}, 2);
  EXPECT_EQ(p.global_pass.photons.size(), 0u);
  EXPECT_EQ(p.global_pass.emitted, 256u * 10u + 65536u);
  EXPECT_NE(p.global_pass.stopped.find("cap"), std::string::npos);
}

TEST(PhotonMaps, OnlyTheMapsASceneNeedsAreTraced) {
  // The furnace has no specular surface: no caustic map, and the stats say why.
  const tracer::RenderResult furnace =
      render(scenes_gen::make_furnace_scene(1.0f, 0.5f, 100.0f), "naive", {{"global_photons", 2000}},
             1, 8, 8);
  EXPECT_EQ(furnace.stats["maps"]["caustic"]["skipped"], "no specular surface");
  EXPECT_EQ(furnace.stats["maps"]["global"]["stored"], 2000);

  // Mirrors only: no diffuse surface, no map at all.
  tracer::Scene mirrors;
  mirrors.materials = {scenes_gen::mirror("m", Color(0.9f))};
  mirrors.geometry.spheres.push_back({{0, 0, -3}, 1.0f, 0});
  mirrors.lights = {scenes_gen::point_light({0, 3, 0}, 100.0f)};
  mirrors.geometry.finalize();
  const tracer::RenderResult r = render(mirrors, "naive", json::object(), 1, 8, 8);
  EXPECT_TRUE(r.stats["maps"]["global"].contains("skipped"));
  EXPECT_TRUE(r.stats["maps"]["caustic"].contains("skipped"));
  EXPECT_EQ(r.rays.photon, 0u);

  // A light inside a closed mirror sphere, a diffuse floor outside: light never reaches a
  // diffuse surface, which the first round finds out.
  tracer::Scene closed = mirrors;
  closed.materials.push_back(scenes_gen::diffuse("floor", Color(0.5f)));
  closed.geometry.spheres[0] = {{0, 3, 0}, 1.0f, 0};
  closed.geometry.planes.push_back({Vec3(0, 1, 0), 0.0f, 1});
  closed.geometry.finalize();
  const photon::PhotonMaps c = maps_of(closed, "naive", {{"global_photons", 1000}}, 2);
  EXPECT_EQ(c.global_pass.photons.size(), 0u);
  EXPECT_NE(c.global_pass.stopped.find("reached a surface with a diffuse part"), std::string::npos)
      << c.global_pass.stopped;
  EXPECT_EQ(c.global_pass.emitted, 1000u);

  // skip_unneeded_maps = false traces the caustic pass of the furnace anyway: with nothing to aim
  // at it emits everywhere, stores nothing (no specular bounce) and runs to its cap. That is the
  // work the check saves.
  const tracer::RenderResult forced =
      render(scenes_gen::make_furnace_scene(1.0f, 0.5f, 100.0f), "naive",
             {{"global_photons", 2000}, {"caustic_photons", 10}, {"skip_unneeded_maps", false}}, 1,
             8, 8);
  const json& caustic = forced.stats["maps"]["caustic"];
  EXPECT_FALSE(caustic.contains("skipped"));
  EXPECT_EQ(caustic["stored"], 0);
  EXPECT_EQ(caustic["emitted"], 256 * 10 + 65536);
  EXPECT_EQ(forced.image.content_hash(), furnace.image.content_hash());  // same light, more work
  EXPECT_GT(forced.rays.photon, furnace.rays.photon + 256u * 10u);
}

// ---------------------------------------------------------------------------------------------

TEST(PhotonKnobs, BadValuesNameTheKnob) {
  const tracer::Scene scene = scenes_gen::make_furnace_scene(1.0f, 0.5f, 100.0f);
  const struct {
    json knobs;
    std::string knob;
  } cases[] = {
      {{{"global_photons", 0}}, "'global_photons'"},
      {{{"global_photons", -5}}, "'global_photons'"},
      {{{"caustic_photons", 0}}, "'caustic_photons'"},
      {{{"k", 0}}, "'k'"},
      {{{"cone_k", 0.99}}, "'cone_k'"},
      {{{"max_radius", 0}}, "'max_radius'"},
      {{{"max_radius", -1.5}}, "'max_radius'"},
      {{{"filter", "gauss"}}, "'filter'"},
      {{{"final_gather_rays", -1}}, "'final_gather_rays'"},
      {{{"photon_tree", "octree"}}, "'photon_tree'"},
      {{{"seed", -1}}, "'seed'"},
      {{{"kk", 3}}, "'kk'"},
  };
  for (const auto& c : cases) {
    try {
      render(scene, "naive", c.knobs, 1, 4, 4);
      ADD_FAILURE() << c.knobs.dump() << " was accepted";
    } catch (const std::exception& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(c.knob), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
  // Photon counts beyond the memory budget fail before anything is traced.
  const auto boxes = scene.geometry.primitive_bounds();
  tracer::RenderOptions o;
  o.limits.max_memory_bytes = 1 << 20;
  try {
    tracer::render(scene, accel::make_accel("naive", json::object(), boxes), o,
                   photon::photon_integrator(), {{"global_photons", 1000000}});
    ADD_FAILURE() << "1e6 photons fit in 1 MiB";
  } catch (const knobs::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("'global_photons'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("memory budget"), std::string::npos) << e.what();
  }
}

TEST(PhotonKnobs, EveryKnobRoundTripsWithItsDefault) {
  const json all = photon::photon_integrator().params(json::object());
  const photon::PhotonParams p = all.get<photon::PhotonParams>();
  EXPECT_EQ(json(p), all);
  for (const char* knob : {"global_photons", "caustic_photons", "k", "max_radius", "filter", "cone_k",
                           "max_photon_depth", "final_gather_rays", "photon_tree", "leaf_size",
                           "cull", "cache_distances", "seed", "skip_unneeded_maps"})
    EXPECT_TRUE(all.contains(knob)) << knob;
  EXPECT_EQ(all["max_radius"], "auto");
}

}  // namespace
