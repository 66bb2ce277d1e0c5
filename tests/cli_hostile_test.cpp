// Hostile input to the accelbench command line: every hostile case we know of (and its neighbours), run
// as a user runs it, with its exact one-line message and exit status. No case may crash, hang,
// read without bound, or print an exception's raw text.

#include "cli_run.h"

#include "accel/isa.h"
#include "test_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using cli_run::CliRun;

/// Runs accelbench with `args` (a shell fragment) in `dir`, under a 60 s timeout.
CliRun accelbench(const fs::path& dir, const std::string& args) {
  return cli_run::run("cd '" + dir.string() + "' && timeout 60 " + std::string(ACCELBENCH_CLI) + " " + args);
}

using test_files::read;

void write_text(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

const std::string kView =
    "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.01\nresolution 16 16\n";

class Hostile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("accelbench_hostile_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// A small valid scene, five.json, and its JSON.
  json five() {
    if (!fs::exists(dir_ / "five.json")) {
      EXPECT_EQ(accelbench(dir_, "gen five -o five.json").status, 0);
    }
    return json::parse(read(dir_ / "five.json"));
  }

  /// A tiny sweep (two scenes, naive and two kd-trees), run to the end into t.json and t.jsonl.
  void run_tiny_sweep() {
    write_text(dir_ / "tiny.json",
               R"({"name": "tiny", "scenes": ["five", "random:30"],
                   "structures": ["naive", {"name": "kdtree", "max_depth": [4, 8]}],
                   "resolution": "16x12", "repetitions": 1, "warmup": 0})");
    const CliRun r = accelbench(dir_, "sweep --config tiny.json --out t.json --quiet");
    ASSERT_EQ(r.status, 0) << r.output;
  }

  std::vector<std::string> jsonl_lines() {
    std::vector<std::string> lines;
    std::istringstream in(read(dir_ / "t.jsonl"));
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
  }
  void write_jsonl(const std::string& name, const std::vector<std::string>& lines) {
    std::string text;
    for (const auto& l : lines) text += l + "\n";
    write_text(dir_ / name, text);
  }

  fs::path dir_;
};

struct HostileCase {
  std::string what;     ///< The hostile input, in words.
  std::string args;     ///< accelbench arguments (run in the test directory).
  std::string message;  ///< The exact last line of output (the message).
  int status = 1;       ///< The exact exit status.
  bool prefix = false;  ///< `message` is a prefix (the rest depends on the machine).
  int lines = 1;        ///< Lines of output: the message, after a summary for a sweep that ran.
};

void expect_case(const fs::path& dir, const HostileCase& c) {
  const CliRun r = accelbench(dir, c.args);
  EXPECT_EQ(r.status, c.status) << c.what << ": " << c.args << "\n" << r.output;
  ASSERT_FALSE(r.output.empty()) << c.what;
  EXPECT_EQ(r.output.back(), '\n') << c.what;
  std::vector<std::string> lines;
  std::istringstream in(r.output);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  EXPECT_EQ(int(lines.size()), c.lines) << c.what << ":\n" << r.output;
  const std::string last = lines.empty() ? "" : lines.back();
  if (c.prefix)
    EXPECT_EQ(last.rfind(c.message, 0), 0u) << c.what << "\n got: " << last;
  else
    EXPECT_EQ(last, c.message) << c.what;
  for (const auto& l : lines) EXPECT_LE(l.size(), 220u) << c.what << ": line too long: " << l;
}

TEST_F(Hostile, ScenesAndSceneFiles) {
  json doc = five();
  // Nesting 100,000 deep: refused while parsing, at the 65th level.
  write_text(dir_ / "deep.json", std::string(100000, '[') + std::string(100000, ']'));
  write_text(dir_ / "deep2.json", "{\"spheres\": " + std::string(100000, '[') + std::string(100000, ']') + "}");
  const std::string deep_path = "/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/...";
  fs::create_symlink("/dev/zero", dir_ / "zero.json");
  fs::create_symlink("/dev/urandom", dir_ / "random.nff");
  fs::create_directories(dir_ / "x.nff");
  fs::create_directories(dir_ / "dir.obj");
  write_text(dir_ / "empty.ply", "");
  ::mkfifo((dir_ / "fifo.json").c_str(), 0644);
  // Duplicate keys: "spheres": [] appended would have rendered an empty scene.
  std::string dup = read(dir_ / "five.json");
  dup.erase(dup.find_last_of('}'));
  write_text(dir_ / "dup.json", dup + ",\n \"spheres\": []\n}\n");
  json big = doc;
  big["spheres"][0]["radius"] = 1e308;
  write_text(dir_ / "r308.json", big.dump());
  write_text(dir_ / "nan.json", R"({"camera": {"vfov": NaN}})");
  write_text(dir_ / "overflow.json", R"({"camera": {"vfov": 1e999}})");
  write_text(dir_ / "big.nff", kView + "s 1e999 0 0 0.5\n");
  write_text(dir_ / "collinear.nff", kView + "p 4\n0 0 0\n1 0 0\n2 0 0\n3 0 0\n");
  write_text(dir_ / "bg.nff", kView + "b -1 0 0\n");
  json huge_normal = doc;
  huge_normal["planes"] = json::array({{{"normal", {1e30, 0, 0}}, {"offset", 0}, {"material", "glass"}}});
  write_text(dir_ / "normal.json", huge_normal.dump());

  const std::vector<HostileCase> cases = {
      {"JSON nested 100,000 deep (render)", "render deep.json",
       "accelbench: deep.json: " + deep_path + ": nested deeper than 64 levels at line 1, column 65"},
      {"JSON nested 100,000 deep (convert)", "convert deep.json -o out.json",
       "accelbench: deep.json: " + deep_path + ": nested deeper than 64 levels at line 1, column 65"},
      {"JSON nested 100,000 deep (tune)", "tune deep.json",
       "accelbench: deep.json: " + deep_path + ": nested deeper than 64 levels at line 1, column 65"},
      {"JSON nested 100,000 deep inside a scene", "render deep2.json",
       "accelbench: deep2.json: /spheres/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/...: "
       "nested deeper than 64 levels at line 1, column 76"},
      {"a scene linked to /dev/zero", "render zero.json",
       "accelbench: zero.json: is a character device, not a regular scene file"},
      {"an NFF scene linked to /dev/urandom", "convert random.nff -o out.json",
       "accelbench: random.nff: is a character device, not a regular scene file"},
      {"a FIFO as a scene", "render fifo.json", "accelbench: fifo.json: is a FIFO, not a regular scene file"},
      {"a directory named x.nff", "convert x.nff -o out.json",
       "accelbench: x.nff: is a directory, not a regular scene file"},
      {"a missing scene", "render missing.json",
       "accelbench: missing.json: cannot open: No such file or directory"},
      {"duplicate keys", "render dup.json",
       "accelbench: dup.json: /spheres: duplicate key at line 203, column 10 (each key may appear only once in an "
       "object)"},
      {"a radius beyond float range", "render r308.json",
       "accelbench: r308.json: /spheres/0/radius: is beyond float range (magnitude at most 3.4e38), got 1e+308"},
      {"a NaN literal", "render nan.json", "accelbench: nan.json: /camera/vfov: must be a finite number, got NaN"},
      {"a number beyond double range", "render overflow.json",
       "accelbench: overflow.json: /camera/vfov: number \"1e999\" is beyond double range (magnitude at most 1.8e308) "
       "at line 1, column 21"},
      {"a plane normal whose squared length overflows, round trip", "convert normal.json -o out.json",
       "wrote out.json: 5 spheres, 1 plane; 3 lights, 6 materials", 0},
      {"NFF: a number beyond double range", "convert big.nff -o out.json",
       "accelbench: big.nff:8: number '1e999' is beyond float range (magnitude at most 3.4e38)"},
      {"NFF: a polygon with collinear points (convert never writes what render rejects)",
       "convert collinear.nff -o out.json",
       "accelbench: collinear.nff:8: 'p' polygon is degenerate: its vertices do not span a plane"},
      {"NFF: a negative background (the JSON loader's rule)", "convert bg.nff -o out.json",
       "accelbench: bg.nff:8: 'b' colour values must be >= 0, got -1.000000"},
      {"an image that cannot fit (default budget)", "render five.json --resolution 65536x65536",
       "accelbench: --resolution: a 65536x65536 image needs 108 GiB, over the memory budget of ", 1, true},
      {"an image that cannot fit (given budget)", "render five.json --resolution 65536x65536 --max-memory 1G",
       "accelbench: --max-memory: 1 GiB cannot hold the 65536x65536 image (108 GiB needed)"},
      {"gen: a billion spheres", "gen grid --count 1000000000 -o g.json",
       "accelbench: grid: count must be in [0, 10000000], got 1000000000"},
      {"gen: more spheres than a scene file holds", "gen grid --count 1000001 -o g.json",
       "accelbench: --count: gen writes scenes of at most 1000000 primitives written one by one (a larger file "
       "would pass the scene-file limit of 256 MiB); grid made 1000001 (sweeps take the generator itself)"},
      {"gen: an unknown model", "gen mesh --model dragon -o m.json",
       "accelbench: unknown model 'dragon' (known: bunny, ogre, nefertiti, beast, igea, teapot, spot, fandisk, or a "
       "path to an .obj or .ply file)"},
      {"gen: a model for a generator that takes none", "gen five --model bunny -o m.json",
       "accelbench: five: takes no model (only mesh and mesh_grid do)"},
      {"convert: a missing model", "convert missing.obj -o m.json", "accelbench: missing.obj: no such file"},
      {"convert: a directory named like a model", "convert dir.obj -o m.json",
       "accelbench: dir.obj: is a directory, not a regular mesh file"},
      {"convert: an empty model", "convert empty.ply -o m.json", "accelbench: empty.ply: is empty"},
      {"convert: a model of an unknown format", "convert model.xyz -o m.json",
       "accelbench: model.xyz: unknown scene format '.xyz' (expected .json or .nff)"},
      {"gen: a negative seed", "gen five --seed -1 -o f.json",
       "accelbench: --seed: expected an integer in [0, 18446744073709551615], got '-1'"},
      {"gen: a seed past 2^64", "gen random --seed 18446744073709551616 -o f.json",
       "accelbench: --seed: expected an integer in [0, 18446744073709551615], got '18446744073709551616'"},
  };
  for (const HostileCase& c : cases) expect_case(dir_, c);
  EXPECT_FALSE(fs::exists(dir_ / "out.json") && read(dir_ / "out.json").find("degenerate") != std::string::npos);
  // The converted scene with the huge normal loads back: its normal was normalised, not zeroed.
  EXPECT_EQ(accelbench(dir_, "render out.json --resolution 8x8 --accel naive").status, 0);
}

#if ACCELBENCH_HAVE_EMBREE
// Embree forced to an instruction set: an unknown name, and a level this CPU lacks, are refused
// in one line naming the knob; every level the CPU has renders.
TEST_F(Hostile, EmbreeInstructionSets) {
  five();
  expect_case(dir_, {"an unknown instruction set", "render five.json --accel embree --knob isa=avx9 --resolution 8x8",
                     "accelbench: embree: knob 'isa' must be one of build|cpu|sse2|sse4.2|avx|avx2|avx512, "
                     "got \"avx9\""});
  const accel::IsaSet cpu = accel::cpu_isas();
  for (accel::Isa isa : accel::kIsas) {
    const std::string name = accel::isa_name(isa);
    const std::string args = "render five.json --accel embree --resolution 8x8 -o o.png --knob isa=" + name;
    if (cpu & accel::isa_bit(isa)) {
      const CliRun r = accelbench(dir_, args);
      EXPECT_EQ(r.status, 0) << name << ": " << r.output;
    } else {
      expect_case(dir_, {"a level this CPU lacks", args,
                         "accelbench: embree: knob 'isa' = " + name + " needs " + accel::isa_features(isa) +
                             ", which this CPU lacks (it has " + accel::isa_list(cpu) + ")"});
    }
  }
}
#endif

TEST_F(Hostile, SweepFilesAndFlags) {
  write_text(dir_ / "deep.json", std::string(100000, '[') + std::string(100000, ']'));
  // A million-element axis: refused with a short line (it printed 6.9 MB).
  json axis = {{"scenes", {"five"}}, {"structures", {{{"name", "kdtree"}, {"max_depth", json::array()}}}}};
  for (int i = 0; i < 1000000; ++i) axis["structures"][0]["max_depth"].push_back(i);
  write_text(dir_ / "axis.json", axis.dump());
  json cross = {{"scenes", {"five", "random:10"}},
                {"structures", {{{"name", "kdtree"}, {"max_depth", json::array()}, {"max_leaf_size", json::array()}}}}};
  for (int i = 0; i < 1000; ++i) {
    cross["structures"][0]["max_depth"].push_back(i);
    cross["structures"][0]["max_leaf_size"].push_back(i + 1);
  }
  write_text(dir_ / "cross.json", cross.dump());
  write_text(dir_ / "bad_key.json", R"({"scenes": ["five"], "structures": ["naive"], "colour": 1})");
  write_text(dir_ / "dup.json", R"({"scenes": ["five"], "structures": ["naive"], "scenes": []})");
  write_text(dir_ / "all_fail.json", R"({"scenes": ["five"], "structures": [{"name": "kdtree", "max_leaf_size": 0}],
                                         "resolution": "8x8", "repetitions": 1, "warmup": 0})");
  fs::create_symlink("/dev/zero", dir_ / "zero.json");
  const std::vector<HostileCase> cases = {
      {"a sweep file nested 100,000 deep", "sweep --config deep.json",
       "accelbench: deep.json: /0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/...: "
       "nested deeper than 64 levels at line 1, column 65"},
      {"a sweep file linked to /dev/zero", "sweep --config zero.json",
       "accelbench: zero.json: is a character device, not a regular sweep file"},
      {"a million-element axis", "sweep --config axis.json",
       "accelbench: axis.json: /structures/0/max_depth: must list at most 10000 values, got 1000000"},
      {"two axes crossed into a million configurations", "sweep --config cross.json",
       "accelbench: cross.json: /: the sweep expands to 2e+06 configurations, more than the limit of 100000 (fewer knob "
       "values or scenes)"},
      {"duplicate keys in a sweep file", "sweep --config dup.json",
       "accelbench: dup.json: /scenes: duplicate key at line 1, column 54 (each key may appear only once in an "
       "object)"},
      {"a bad key in the file, flags given: the file is named, not the flags", "sweep --config bad_key.json --accel naive",
       "accelbench: bad_key.json: /colour: unknown key"},
      {"a scene given twice in --scenes", "sweep --scenes five,five --accel naive",
       "accelbench: --scenes: scene name 'five' is given twice"},
      {"a knob flag no swept structure has", "sweep --scenes five --accel naive,bvh --placement leaves",
       "accelbench: --placement: no swept structure has the knob placement (swept: naive, bvh)"},
      {"an unknown structure in --accel", "sweep --scenes five --accel naive,kdtre",
       "accelbench: --accel: unknown structure 'kdtre' (known: ", 1, true},
      {"a sweep whose every row fails", "sweep --config all_fail.json --out af.json --quiet",
       "accelbench: sweep: every configuration failed or is in error (1 row; the reasons are in af.json)", 1, false,
       2},
      {"tune: a bad --placement, before anything is measured", "tune five --placement x",
       "accelbench: --placement: ", 1, true},
      {"tune: a budget too small for anything", "tune five --max-memory 1",
       "accelbench: --max-memory: 1 B cannot hold the 320x240 image (2 MiB needed)"},
      {"tune: a budget too small for the structure, before naive is measured",
       "tune random:100000 --max-memory 1M --resolution 8x8",
       "accelbench: --max-memory: kdtree cannot be built on random-100000 at its default knobs: kdtree: build needs "
       "more than 1.0 MiB (--max-memory); ", 1, true},
      {"tune: a bad --seed", "tune random:10 --seed -1",
       "accelbench: --seed: expected an integer in [0, 18446744073709551615], got '-1'"},
      {"tune: a structure without the knob", "tune five --accel bvh --placement leaves",
       "accelbench: --placement: bvh has no knob 'placement'"},
  };
  for (const HostileCase& c : cases) expect_case(dir_, c);
}

TEST_F(Hostile, ResumeAndMerge) {
  run_tiny_sweep();
  const auto lines = jsonl_lines();
  ASSERT_EQ(lines.size(), 1u + 6u + 1u);  // header, six rows, a run record
  json row = json::parse(lines[1]);
  auto with_row = [&](const json& r) {
    std::vector<std::string> out = lines;
    out[1] = r.dump();
    return out;
  };
  json r = row;
  r["key"] = "five|naive|{\"x\":1}";
  write_jsonl("bogus_key.jsonl", with_row(r));
  r = row;
  r.erase("key");
  write_jsonl("no_key.jsonl", with_row(r));
  r = row;
  r["key"] = 5;
  write_jsonl("number_key.jsonl", with_row(r));
  r = row;
  r["index"] = 3;
  write_jsonl("wrong_index.jsonl", with_row(r));
  std::vector<std::string> twice = lines;
  twice.insert(twice.begin() + 2, lines[1]);
  write_jsonl("twice.jsonl", twice);
  std::string garbage;
  for (int i = 0; i < 4096; ++i) garbage += char((i * 37) % 256);
  write_text(dir_ / "garbage.jsonl", garbage);
  std::vector<std::string> middle = lines;
  middle[3] = middle[3].substr(0, 20);
  write_jsonl("middle.jsonl", middle);

  const std::string sweep = "sweep --config tiny.json --out r.json --quiet --resume --jsonl ";
  const std::vector<HostileCase> cases = {
      {"resume: a row whose key is corrupted", sweep + "bogus_key.jsonl",
       "accelbench: bogus_key.jsonl:2: /key: \"five|naive|{\\\"x\\\":1}\" is not a configuration of this sweep (in "
       "shard {\"count\":1,\"index\":0}); cannot --resume"},
      {"resume: a row without a key", sweep + "no_key.jsonl",
       "accelbench: no_key.jsonl:2: /key: missing (in shard {\"count\":1,\"index\":0}); cannot --resume"},
      {"resume: a row whose key is a number", sweep + "number_key.jsonl",
       "accelbench: number_key.jsonl:2: /key: must be a string, got 5 (in shard {\"count\":1,\"index\":0}); cannot "
       "--resume"},
      {"resume: a row at the wrong index", sweep + "wrong_index.jsonl",
       "accelbench: wrong_index.jsonl:2: /index: must be 0 (the index of \"five|naive|{}\"), got 3 (in shard "
       "{\"count\":1,\"index\":0}); cannot --resume"},
      {"resume: a configuration twice", sweep + "twice.jsonl",
       "accelbench: twice.jsonl:3: configuration \"five|naive|{}\" is already on line 2; cannot --resume"},
      {"resume: a file of binary garbage", sweep + "garbage.jsonl",
       "accelbench: garbage.jsonl:1: (root): invalid JSON: ", 1, true},
      {"resume: a line cut in the middle of the file", sweep + "middle.jsonl",
       "accelbench: middle.jsonl:4: ", 1, true},
  };
  for (const HostileCase& c : cases) {
    const std::string file = c.args.substr(c.args.rfind(' ') + 1);
    const std::string before = read(dir_ / file);
    expect_case(dir_, c);
    EXPECT_EQ(read(dir_ / file), before) << c.what << ": the file was changed";
    EXPECT_FALSE(fs::exists(dir_ / "r.json")) << c.what << ": a results file was written";
  }

  // merge: rows and shard metadata are checked against the sweep they claim to belong to.
  const json results = json::parse(read(dir_ / "t.json"));
  json m = results;
  m["rows"][0]["key"] = 5;
  write_text(dir_ / "m_key.json", m.dump());
  m = results;
  m["shard"] = {{"index", 5}, {"count", 2}};
  write_text(dir_ / "m_shard.json", m.dump());
  m = results;
  m["rows"][0]["index"] = 99999999;
  write_text(dir_ / "m_index.json", m.dump());
  m = results;
  m["shard"] = {{"index", 1}, {"count", 2}};
  write_text(dir_ / "m_other_shard.json", m.dump());
  m = results;
  m["rows"][1]["key"] = m["rows"][0]["key"];
  write_text(dir_ / "m_twice.json", m.dump());
  write_text(dir_ / "m_deep.json", std::string(100000, '[') + std::string(100000, ']'));
  const std::vector<HostileCase> merge_cases = {
      {"merge: a row whose key is a number", "merge m_key.json -o all.json",
       "accelbench: m_key.json: /rows/0/key: must be a string, got 5"},
      {"merge: shard index 5 of 2", "merge m_shard.json -o all.json",
       "accelbench: m_shard.json: /shard/index: must be in [0, 1] (count is 2), got 5"},
      {"merge: row index 99999999", "merge m_index.json -o all.json",
       "accelbench: m_index.json: /rows/0/index: must be 0 (the index of \"five|naive|{}\"), got 99999999"},
      {"merge: a row outside the file's shard", "merge m_other_shard.json -o all.json",
       "accelbench: m_other_shard.json: /rows/0/index: 0 is not in shard 1/2"},
      {"merge: one configuration twice in a file", "merge m_twice.json -o all.json",
       "accelbench: m_twice.json: /rows/1/index: must be 0 (the index of \"five|naive|{}\"), got 1"},
      {"merge: nested 100,000 deep", "merge m_deep.json -o all.json",
       "accelbench: m_deep.json: /0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/...: "
       "nested deeper than 64 levels at line 1, column 65"},
  };
  for (const HostileCase& c : merge_cases) expect_case(dir_, c);
  EXPECT_FALSE(fs::exists(dir_ / "all.json"));
}

}  // namespace
