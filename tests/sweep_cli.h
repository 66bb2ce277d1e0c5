#pragma once
// Running `accelbench sweep` from the sweep tests on a tiny definition, and reading what it
// wrote.

#include "cli/commands.h"

#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstddef>
#include <cstdio>
#include <functional>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace sweep_cli {

using nlohmann::json;
namespace fs = std::filesystem;

/// A fresh, empty directory for one test.
inline fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("accelbench_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// Runs the command line in a forked child, as `accelbench ARGS` would run (stderr silenced),
/// with `after_row` injected into the sweep (cli::Hooks); returns the raw wait status.
inline int run_cli(const std::vector<std::string>& args,
                   std::function<void(std::size_t rows_written)> after_row = {}) {
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    if (!freopen("/dev/null", "w", stderr)) _exit(126);
    std::vector<std::string> copy = args;
    copy.insert(copy.begin(), "accelbench");
    std::vector<char*> argv;
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    const int status = cli::run(int(copy.size()), argv.data(), cli::Hooks{std::move(after_row)});
    std::fflush(nullptr);
    _exit(status);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

/// A hook that sends this process `signal` once `rows` rows are written: SIGKILL runs no
/// clean-up code at all, SIGTERM asks the sweep to stop cleanly.
inline std::function<void(std::size_t)> signal_after(std::size_t rows, int signal) {
  return [rows, signal](std::size_t written) {
    if (written == rows) std::raise(signal);
  };
}

inline json read_json(const fs::path& p) {
  std::ifstream in(p);
  return json::parse(in);
}

/// key -> (status, image hash): what a sweep found, without its timings.
inline std::map<std::string, std::pair<std::string, std::string>> outcome(const json& results) {
  std::map<std::string, std::pair<std::string, std::string>> out;
  for (const auto& r : results["rows"]) out[r["key"]] = {r["status"], r.value("image_hash", "")};
  return out;
}

inline std::vector<std::string> tiny_sweep_args(const fs::path& dir, const std::string& name) {
  return {"sweep",   "--config", (dir / "tiny.json").string(), "--out", (dir / (name + ".json")).string(),
          "--quiet"};
}

inline void write_tiny_definition(const fs::path& dir) {
  std::ofstream(dir / "tiny.json") << json{
      {"name", "tiny"},
      {"scenes", {"random:30", "grid:8"}},
      {"structures", {"naive", {{"name", "octree"}, {"max_depth", {1, 3}}, {"max_leaf_size", {0, 2}}}, "kdtree", "bvh"}},
      {"resolution", "12x9"},
      {"repetitions", 1},
      {"warmup", 0}}.dump();
}

/// True when `doc` validates against results/schema/results.schema.json (Python's jsonschema).
inline bool valid_against_schema(const json& doc, const fs::path& dir) {
  std::ofstream(dir / "validate.py") << "import json, sys\nimport jsonschema\n"
                                        "schema = json.load(open(sys.argv[1]))\n"
                                        "doc = json.load(open(sys.argv[2]))\n"
                                        "errors = list(jsonschema.Draft202012Validator(schema).iter_errors(doc))\n"
                                        "for e in errors[:5]: print(list(e.absolute_path), e.message[:200])\n"
                                        "sys.exit(1 if errors else 0)\n";
  std::ofstream(dir / "doc.json") << doc.dump();
  const std::string cmd = std::string(ACCELBENCH_PYTHON) + " " + (dir / "validate.py").string() + " " +
                          ACCELBENCH_SOURCE_DIR "/results/schema/results.schema.json " + (dir / "doc.json").string();
  return std::system(cmd.c_str()) == 0;
}

}  // namespace sweep_cli
