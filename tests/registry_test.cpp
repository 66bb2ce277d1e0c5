// The structure registry (accel/registry.h) is the only list of structures: every list derived
// from it (the factory's names, the command line, the sweeps' knob discovery, the benchmarks,
// the plot script's registry file and the knob reference in the docs) holds every entry.

#include "accel/accel.h"
#include "integrators/integrators.h"
#include "harness/sweep_definition.h"
#include "scenes_gen/generators.h"

#include "cli_run.h"
#include "test_files.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <set>
#include <string>

namespace {

using nlohmann::json;

using ProcessRun = cli_run::CliRun;
using cli_run::run;

using test_files::read;

std::vector<std::string> registry_names() {
  std::vector<std::string> out;
  accel::for_each_entry([&]<class E>() { out.push_back(E::kName); });
  return out;
}

TEST(Registry, FactoryNamesAreTheRegistry) {
  const std::vector<std::string> names = registry_names();
  EXPECT_EQ(accel::accel_names(), names);
  ASSERT_GE(names.size(), 6u);
  for (const std::string& n : names) {
    const accel::StructureInfo* s = accel::find_structure(n);
    ASSERT_NE(s, nullptr) << n;
    if (!s->built) {
      EXPECT_FALSE(s->missing.empty()) << n;
      continue;
    }
    // Every built entry builds; a structure reports its name and every knob, a selector says
    // that it chose.
    const accel::AnyAccel a = accel::make_accel(n, json::object(), std::vector<accel::Aabb>{});
    if (s->selector) {
      EXPECT_EQ(a.selected_by.at("structure"), n);
    } else {
      EXPECT_EQ(accel::name_of(a), n);
      EXPECT_EQ(accel::params_of(a).size(), s->knobs.size()) << n;
    }
  }
}

/// Names that appear twice in `names`.
std::set<std::string> repeated(const std::vector<std::string>& names) {
  std::set<std::string> seen, twice;
  for (const std::string& n : names)
    if (!seen.insert(n).second) twice.insert(n);
  return twice;
}

TEST(Registry, NamesAreUniqueInEveryTable) {
  EXPECT_EQ(repeated(registry_names()), std::set<std::string>{});
  std::vector<std::string> integrator_names;
  for (const tracer::Integrator* i : integrators::all()) {
    integrator_names.push_back(std::string(i->name));
    EXPECT_EQ(repeated(i->knob_table().names()), std::set<std::string>{}) << i->name;
  }
  EXPECT_EQ(repeated(integrator_names), std::set<std::string>{});
  EXPECT_EQ(repeated(scenes_gen::generator_names()), std::set<std::string>{});
  for (const accel::StructureInfo& s : accel::structures()) EXPECT_EQ(repeated(s.knobs), std::set<std::string>{}) << s.name;
}

// The integrator table reaches the command line (render's --integrator and `integrators`),
// the sweeps, and the docs' generated knob reference; every integrator completes its own knobs
// and reads them back unchanged.
TEST(Registry, EveryIntegratorReachesTheCommandLineSweepsAndDocs) {
  const ProcessRun help = run(std::string(ACCELBENCH_CLI) + " render --help");
  ProcessRun list = run(std::string(ACCELBENCH_CLI) + " integrators");
  list.output = "\n" + list.output;
  ASSERT_EQ(list.status, 0) << list.output;
  ASSERT_GE(integrators::all().size(), 4u);
  for (const tracer::Integrator* i : integrators::all()) {
    const std::string n(i->name);
    EXPECT_NE(help.output.find(n), std::string::npos) << n << " missing from render --help";
    EXPECT_NE(list.output.find("\n" + n + " "), std::string::npos) << n << " missing from `integrators`";
    EXPECT_NO_THROW(harness::parse_sweep_definition(
        {{"scenes", {"five"}}, {"structures", {{{"name", "naive"}}}}, {"integrator", n}})) << n;
    const json defaults = i->params(json::object());
    EXPECT_EQ(i->params(defaults), defaults) << n;
    EXPECT_EQ(defaults.size(), i->knob_table().names().size()) << n;
  }
  const ProcessRun md = run(std::string(ACCELBENCH_CLI) + " integrators --markdown");
  EXPECT_EQ(md.output, integrators::markdown());
  EXPECT_NE(read(ACCELBENCH_SOURCE_DIR "/docs/tracer.md").find(integrators::markdown()), std::string::npos)
      << "docs/tracer.md: paste the output of `accelbench integrators --markdown` under its knob reference";
}

// The generator table reaches `accelbench gen`, the sweeps' scene items and the docs.
TEST(Registry, EveryGeneratorReachesTheCommandLineSweepsAndDocs) {
  const ProcessRun help = run(std::string(ACCELBENCH_CLI) + " gen --help");
  ASSERT_EQ(help.status, 0) << help.output;
  const ProcessRun list = run(std::string(ACCELBENCH_CLI) + " gen --list");
  ASSERT_EQ(list.status, 0) << list.output;
  EXPECT_NE(read(ACCELBENCH_SOURCE_DIR "/docs/scene-format.md").find("```\n" + list.output + "```"), std::string::npos)
      << "docs/scene-format.md: paste the output of `accelbench gen --list` under Generators";
  ASSERT_GE(scenes_gen::generator_names().size(), 6u);
  for (const std::string& n : scenes_gen::generator_names()) {
    EXPECT_NE(help.output.find(n), std::string::npos) << n << " missing from gen --help";
    EXPECT_EQ(harness::parse_scene_item(n).name, n);
  }
}

TEST(Registry, CommandLineListsEveryStructure) {
  const ProcessRun help = run(std::string(ACCELBENCH_CLI) + " render --help");
  ProcessRun list = run(std::string(ACCELBENCH_CLI) + " structures");
  list.output = "\n" + list.output;
  ASSERT_EQ(list.status, 0) << list.output;
  for (const std::string& n : registry_names()) {
    EXPECT_NE(help.output.find(n), std::string::npos) << n << " missing from render --help";
    EXPECT_NE(list.output.find("\n" + n + " "), std::string::npos) << n << " missing from `structures`";
  }
}

TEST(Registry, SweepsKnowEveryStructureAndItsKnobs) {
  for (const accel::StructureInfo& s : accel::structures()) {
    EXPECT_EQ(harness::structure_knobs(s.name), s.knobs) << s.name;
    json entry = {{"name", s.name}};
    for (const json& k : s.knob_table) entry[k.at("name").get<std::string>()] = k.at("default");
    EXPECT_NO_THROW(harness::parse_sweep_definition({{"scenes", {"five"}}, {"structures", {entry}}})) << s.name;
  }
}

TEST(Registry, BenchmarksCoverEveryBuiltStructure) {
#ifdef ACCELBENCH_BENCH_TRACE
  const ProcessRun list = run(std::string(ACCELBENCH_BENCH_TRACE) + " --benchmark_list_tests=true");
  ASSERT_EQ(list.status, 0) << list.output;
  // A peer native on triangles is measured on the mesh scenes (present with the shared models),
  // one native on spheres on the sphere scenes; every other structure on both.
  const bool meshes = list.output.find("Trace/bunny/") != std::string::npos;
  if (!meshes) std::printf("no mesh rows (the shared models are absent): peers native on triangles are not checked\n");
  const auto on_meshes = [](const accel::StructureInfo& s) { return s.native_shapes == "triangles"; };
  const auto scene_of = [&](const accel::StructureInfo& s) { return on_meshes(s) ? "bunny" : "spheres8000"; };
  for (const accel::StructureInfo& s : accel::structures()) {
    if (!s.built || (!meshes && on_meshes(s))) continue;
    const std::string scene = scene_of(s);
    for (const char* set : {"coherent", "packets", "incoherent", "shadow"})
      EXPECT_NE(list.output.find("Trace/" + scene + "/" + std::string(set) + "/" + s.name + "\n"), std::string::npos)
          << s.name;
    if (meshes && s.native_shapes != "spheres") {
      EXPECT_NE(list.output.find("Trace/bunny/coherent/" + s.name + "\n"), std::string::npos) << s.name;
    }
    if (s.name != "naive") {
      EXPECT_NE(list.output.find("Render/" + scene + "/" + s.name + "/"), std::string::npos) << s.name;
    }
    // Every structure of ours rendered in pairs with each peer (Embree) on the peer's scenes,
    // where Embree is built.
    if (ACCELBENCH_HAVE_EMBREE && s.name != "naive" && !s.peer) {
      for (const accel::StructureInfo& peer : accel::structures())
        if (peer.peer && peer.built && (meshes || !on_meshes(peer))) {
          EXPECT_NE(list.output.find("RenderPair/" + std::string(scene_of(peer)) + "/" + s.name + "/vs_" +
                                     peer.name + "/"),
                    std::string::npos)
              << s.name << " vs " << peer.name;
        }
    }
  }
#else
  GTEST_SKIP() << "bench_trace is not built (ACCELBENCH_BENCHMARKS=OFF)";
#endif
}

// Every generator and every integrator has its whole-render benchmark (bench/bench_render.cpp),
// the mesh generators where the shared models are.
TEST(Registry, BenchmarksCoverEveryGeneratorAndIntegrator) {
#ifdef ACCELBENCH_BENCH_RENDER
  ProcessRun list = run(std::string(ACCELBENCH_BENCH_RENDER) + " --benchmark_list_tests=true 2>&1");
  ASSERT_EQ(list.status, 0) << list.output;
  list.output = "\n" + list.output;
  const bool meshes = list.output.find("\nGenerator/mesh/") != std::string::npos;
  if (!meshes) std::printf("no mesh generator rows (the shared models are absent)\n");
  for (const std::string& n : scenes_gen::generator_names()) {
    if (meshes || !scenes_gen::generator_takes_model(n)) {
      EXPECT_NE(list.output.find("\nGenerator/" + n + "/"), std::string::npos) << n;
    }
  }
  for (const tracer::Integrator* i : integrators::all())
    EXPECT_NE(list.output.find("\nIntegrator/" + std::string(i->name) + "/cornell/"), std::string::npos) << i->name;
#else
  GTEST_SKIP() << "bench_render is not built (ACCELBENCH_BENCHMARKS=OFF)";
#endif
}

// The paired render benchmark validates both structures, renders both, and reports the peer's time
// over the structure's as a counter (one render of spheres8000 at 1024x768 each, about a second).
TEST(Registry, RenderPairReportsThePeersTimeOverOurs) {
#if defined(ACCELBENCH_BENCH_TRACE) && ACCELBENCH_HAVE_EMBREE
  const ProcessRun r = run(std::string(ACCELBENCH_BENCH_TRACE) +
                           " --benchmark_filter='^RenderPair/spheres8000/bvh8/vs_embree/' --benchmark_format=json 2>&1");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string ratio_key = "\"peer_ms_over_this\": ", rays_key = "\"rays_per_render\": ";
  const std::size_t at = r.output.find(ratio_key);
  ASSERT_NE(at, std::string::npos) << r.output;
  const double ratio = std::stod(r.output.substr(at + ratio_key.size()));
  // A ratio of two renders of the same image: positive and finite, whatever the host does.
  EXPECT_GT(ratio, 0.05) << r.output;
  EXPECT_LT(ratio, 20.0) << r.output;
  const std::size_t rays_at = r.output.find(rays_key);
  ASSERT_NE(rays_at, std::string::npos) << r.output;
  EXPECT_GE(std::stod(r.output.substr(rays_at + rays_key.size())), 1024.0 * 768.0) << "a camera ray per pixel at least";
#else
  GTEST_SKIP() << "needs bench_trace and Embree";
#endif
}

TEST(Registry, PlotScriptReadsTheCurrentRegistryFile) {
  // scripts/structures.json is `accelbench structures --json`, committed for scripts/plot.py.
  const json committed = json::parse(read(ACCELBENCH_SOURCE_DIR "/scripts/structures.json"));
  EXPECT_EQ(committed, accel::registry_json())
      << "regenerate it: build/bin/accelbench structures --json > scripts/structures.json";
  // Every structure (not selector) gets a colour and a place in plot.py's order.
  const ProcessRun py = run(std::string(ACCELBENCH_PYTHON) + " -c \"import sys; sys.path.insert(0, '" ACCELBENCH_SOURCE_DIR
                     "/scripts'); import plot; print('\\n'.join(plot.VARIANT_ORDER)); "
                     "print('\\n'.join(plot.variant({'structure': s['name']}) for s in plot.REGISTRY))\"");
  ASSERT_EQ(py.status, 0) << py.output;
  for (const accel::StructureInfo& s : accel::structures()) {
    if (s.selector) continue;
    EXPECT_NE(py.output.find(s.name), std::string::npos) << s.name << " missing from plot.py's variants";
  }
}

TEST(Registry, DocsHoldTheGeneratedKnobReference) {
  const std::string doc = read(ACCELBENCH_SOURCE_DIR "/docs/structures.md");
  EXPECT_NE(doc.find(accel::knob_reference_markdown()), std::string::npos)
      << "regenerate the knob reference in docs/structures.md: build/bin/accelbench structures --markdown";
  for (const std::string& n : registry_names()) EXPECT_NE(doc.find("| `" + n + "` |"), std::string::npos) << n;
}

}  // namespace
