// Knob tables (accel/knob_table.h): JSON in and out, defaults read from the struct, one-line
// errors for unknown knobs, wrong types and values out of range, command-line values, and the
// same error text wherever a knob is given: JSON to the factory, a sweep file, `--knob`.

#include "accel/accel.h"
#include "knobs/knob_table.h"
#include "harness/sweep_definition.h"
#include "harness/sweep_measure.h"
#include "scenes_gen/generators.h"

#include "cli_run.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace {

using knobs::ConfigError;
using knobs::Knob;
using knobs::KnobTable;
using nlohmann::json;

enum class Flavour : std::uint8_t { Plain, Fancy };

/// A parameter struct that is not a structure's: the table is generic.
struct Demo {
  int depth = 5;
  float radius = 0.25f;
  bool fast = true;
  Flavour flavour = Flavour::Fancy;
  std::uint64_t photons = 1000;

  static const KnobTable<Demo>& knobs() {
    using K = Knob<Demo>;
    static const KnobTable<Demo> t(
        "demo", {K::integer("depth", &Demo::depth, 0, 10, "levels", "How deep."),
                 K::number("radius", &Demo::radius, 0.0, 2.0, "world units", "How wide."),
                 K::boolean("fast", &Demo::fast, "Whether to hurry."),
                 K::choice("flavour", &Demo::flavour, {{"plain", Flavour::Plain}, {"fancy", Flavour::Fancy}},
                           "Which flavour.")
                     .variant(),
                 K::integer("photons", &Demo::photons, 1, 1'000'000'000'000LL, "photons", "How many.")});
    return t;
  }
};

std::string table_error(const json& j) {
  try {
    Demo::knobs().from_json(j);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(KnobTable, DefaultsComeFromTheStructAndRoundTrip) {
  const json d = Demo::knobs().to_json(Demo{});
  EXPECT_EQ(d, json({{"depth", 5}, {"radius", 0.25}, {"fast", true}, {"flavour", "fancy"}, {"photons", 1000}}));
  Demo p;
  p.depth = 7;
  p.flavour = Flavour::Plain;
  p.photons = 5'000'000'000ull;
  const json j = Demo::knobs().to_json(p);
  const Demo q = Demo::knobs().from_json(j);
  EXPECT_EQ(q.depth, 7);
  EXPECT_EQ(q.flavour, Flavour::Plain);
  EXPECT_EQ(q.photons, 5'000'000'000ull);
  EXPECT_EQ(Demo::knobs().to_json(q), j);
  // Absent keys keep the defaults; null is "all defaults".
  EXPECT_EQ(Demo::knobs().from_json({{"fast", false}}).depth, 5);
  EXPECT_EQ(Demo::knobs().from_json(nullptr).radius, 0.25f);
  EXPECT_EQ(Demo::knobs().find("radius")->default_value(), json(0.25));
}

TEST(KnobTable, ErrorsAreOneLineNamingOwnerAndKnob) {
  EXPECT_EQ(table_error({{"dept", 1}}), "demo: unknown knob 'dept' (its knobs: depth, radius, fast, flavour, photons)");
  EXPECT_EQ(table_error({{"depth", "3"}}), "demo: knob 'depth' must be an integer, got \"3\"");
  EXPECT_EQ(table_error({{"depth", 2.5}}), "demo: knob 'depth' must be an integer, got 2.5");
  EXPECT_EQ(table_error({{"depth", 11}}), "demo: knob 'depth' must be in [0, 10], got 11");
  EXPECT_EQ(table_error({{"depth", -1}}), "demo: knob 'depth' must be in [0, 10], got -1");
  EXPECT_EQ(table_error({{"depth", 18446744073709551615ull}}),
            "demo: knob 'depth' must be in [0, 10], got 18446744073709551615");
  EXPECT_EQ(table_error({{"radius", 3}}), "demo: knob 'radius' must be in [0.0, 2.0], got 3");
  EXPECT_EQ(table_error({{"radius", "wide"}}), "demo: knob 'radius' must be a number, got \"wide\"");
  EXPECT_EQ(table_error({{"fast", 1}}), "demo: knob 'fast' must be true or false, got 1");
  EXPECT_EQ(table_error({{"flavour", "sour"}}), "demo: knob 'flavour' must be one of plain|fancy, got \"sour\"");
  EXPECT_EQ(table_error({{"flavour", 0}}), "demo: knob 'flavour' must be one of plain|fancy, got 0");
  EXPECT_EQ(table_error(json::array({1})), "demo: knobs must be a JSON object, got [1]");
  EXPECT_EQ(table_error({{"photons", 0}}), "demo: knob 'photons' must be in [1, 1000000000000], got 0");
  // A struct filled in code gets the same checks.
  Demo bad;
  bad.depth = 99;
  EXPECT_THROW(Demo::knobs().validate(bad), ConfigError);
}

TEST(KnobTable, CommandLineValuesAreReadAsJsonScalarsElseStrings) {
  EXPECT_EQ(knobs::knob_value_from_text("8"), json(8));
  EXPECT_EQ(knobs::knob_value_from_text("-2.5"), json(-2.5));
  EXPECT_EQ(knobs::knob_value_from_text("true"), json(true));
  EXPECT_EQ(knobs::knob_value_from_text("sah"), json("sah"));
  EXPECT_EQ(knobs::knob_value_from_text("8x"), json("8x"));
  EXPECT_EQ(knobs::knob_value_from_text(""), json(""));
  EXPECT_EQ(knobs::parse_knob_assignment("max_depth=8"), std::make_pair(std::string("max_depth"), json(8)));
  EXPECT_EQ(knobs::parse_knob_assignment("split=sah").second, json("sah"));
  try {
    knobs::parse_knob_assignment("max_depth");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "--knob: expected NAME=VALUE, got 'max_depth'");
  }
  EXPECT_THROW(knobs::parse_knob_assignment("=3"), ConfigError);
}

TEST(KnobTable, MarkdownAndDescriptionListEveryKnob) {
  const std::string md = Demo::knobs().markdown();
  for (const char* k : {"`depth`", "`radius`", "`fast`", "`flavour`", "`photons`", "[0, 10]", "`plain`, `fancy`", "How wide."})
    EXPECT_NE(md.find(k), std::string::npos) << k;
  const json d = Demo::knobs().describe();
  ASSERT_EQ(d.size(), 5u);
  EXPECT_EQ(d[3]["choices"], json({"plain", "fancy"}));
  EXPECT_TRUE(d[3]["variant"].get<bool>());
  EXPECT_EQ(d[0]["default"], 5);
}

// ---------------------------------------------------------------------------------------------
// The same errors everywhere: the factory's JSON, a sweep file, and --knob on the command line.

using cli_run::CliRun;

using cli_run::accelbench;

std::string factory_error(const std::string& structure, const json& knobs) {
  try {
    accel::make_accel(structure, knobs, std::vector<accel::Aabb>{});
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

/// A sweep file's verdict on a structure entry with these knobs: an unknown knob stops the
/// parse (after the JSON pointer); a bad value fails that configuration's row, with its reason.
std::string sweep_error(const std::string& structure, const json& knobs) {
  json structure_entry = knobs;
  structure_entry["name"] = structure;
  try {
    harness::parse_sweep_definition({{"scenes", {"five"}}, {"structures", {structure_entry}}});
  } catch (const harness::SweepError& e) {
    return e.what();
  }
  static const tracer::Scene scene = scenes_gen::generate("five", scenes_gen::GenOptions{});
  const harness::Measurement m =
      harness::measure(scene, scene.geometry.primitive_bounds(), structure, knobs, harness::MeasureOptions{}, std::nullopt);
  return m.status == harness::RowStatus::Failed ? "row failed: " + m.reason : "(no error)";
}

TEST(KnobTable, SameErrorFromJsonSweepFileAndKnobFlag) {
  const std::filesystem::path scene =
      std::filesystem::temp_directory_path() / ("knob_table_test_" + std::to_string(::getpid()) + ".json");
  ASSERT_EQ(accelbench("gen five -o " + scene.string()).status, 0);
  struct Case {
    std::string structure, knob, text;  ///< text: as given to --knob
  };
  const std::vector<Case> cases = {{"bvh", "max_dept", "3"},      {"bvh", "max_depth", "65"},
                                   {"bvh", "max_depth", "deep"},  {"kdtree", "split", "median"},
                                   {"kdtree", "empty_bonus", "2"}, {"octree", "max_leaf_size", "0"}};
  for (const Case& c : cases) {
    const json knobs = {{c.knob, knobs::knob_value_from_text(c.text)}};
    const std::string from_json = factory_error(c.structure, knobs);
    ASSERT_EQ(from_json.rfind(c.structure + ": ", 0), 0u) << from_json;
    // A sweep file: an unknown knob is named before anything runs, after its JSON pointer; a bad
    // value fails its row with the same message.
    const bool unknown = from_json.find("unknown knob") != std::string::npos;
    EXPECT_EQ(sweep_error(c.structure, knobs),
              unknown ? "/structures/0/" + c.knob + ": " + from_json : "row failed: " + from_json);
    const CliRun run = accelbench("render " + scene.string() + " --resolution 8x8 --accel " + c.structure +
                                  " --knob " + c.knob + "=" + c.text);
    EXPECT_NE(run.status, 0);
    EXPECT_EQ(run.output, "accelbench: " + from_json + "\n");
  }
  std::filesystem::remove(scene);
}

}  // namespace
