#include "harness/sweep_machine.h"

#include "accel/isa.h"

#include <sys/utsname.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <memory>
#include <set>
#include <thread>
#include <tuple>
#include <vector>

// Set by harness/CMakeLists.txt; the fallbacks keep the file compilable on its own.
#ifndef ACCELBENCH_GIT_COMMIT
#define ACCELBENCH_GIT_COMMIT "unknown"
#endif
#ifndef ACCELBENCH_BUILD_TYPE
#define ACCELBENCH_BUILD_TYPE "unknown"
#endif
#ifndef ACCELBENCH_CXX_FLAGS
#define ACCELBENCH_CXX_FLAGS "unknown"
#endif
#ifndef ACCELBENCH_SOURCE_DIR
#define ACCELBENCH_SOURCE_DIR "."
#endif

namespace harness {
namespace {

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) {
        auto start = line.find_first_not_of(' ', colon + 1);
        return start == std::string::npos ? std::string() : line.substr(start);
      }
    }
  }
  return "unknown";
}

std::string compiler() {
#if defined(__clang__)
  return std::string("clang ") + __clang_version__;
#elif defined(__GNUC__)
  return std::string("gcc ") + __VERSION__;
#else
  return "unknown";
#endif
}

/// `git rev-parse HEAD` in the source tree when git and the tree are there, else "".
std::string runtime_git_commit() {
  const std::string cmd = "git -C '" ACCELBENCH_SOURCE_DIR "' rev-parse HEAD 2>/dev/null";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  if (!pipe) return "";
  std::array<char, 128> buf{};
  std::string out;
  while (fgets(buf.data(), int(buf.size()), pipe.get())) out += buf.data();
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out.size() == 40 ? out : "";
}

std::vector<std::string> isa_names(accel::IsaSet set) {
  std::vector<std::string> out;
  for (accel::Isa isa : accel::isas_in(set)) out.push_back(accel::isa_name(isa));
  return out;
}

}  // namespace

std::string utc_now_iso8601() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

nlohmann::json machine_info() {
  utsname u{};
  uname(&u);
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  const std::string built = ACCELBENCH_GIT_COMMIT, now = runtime_git_commit();
  return {{"cpu_model", cpu_model()},
          {"cores", std::thread::hardware_concurrency()},
          {"memory_bytes", pages > 0 && page > 0 ? std::uint64_t(pages) * std::uint64_t(page) : 0},
          {"os", std::string(u.sysname) + " " + u.release + " " + u.machine},
          {"hostname", std::string(u.nodename)},
          {"compiler", compiler()},
          {"flags", ACCELBENCH_CXX_FLAGS},
          // The instruction set the numbers were measured at: the level this build targets (its
          // SIMD width and Embree's default), and every level the CPU has.
          {"isa", {{"build", accel::isa_name(accel::build_isa())}, {"cpu", isa_names(accel::cpu_isas())}}},
          {"build_type", ACCELBENCH_BUILD_TYPE},
          {"git_commit", now.empty() ? built : now},
          {"git_commit_at_build", built},
          {"date", utc_now_iso8601()}};
}

namespace {

/// A string field of a machine description, `otherwise` when absent or not a string.
std::string text_field(const nlohmann::json& machine, const char* key,
                       const std::string& otherwise) {
  if (!machine.is_object() || !machine.contains(key) || !machine[key].is_string()) return otherwise;
  return machine[key].get<std::string>();
}

/// The core count of a machine description, -1 when absent or not an integer.
long long cores_field(const nlohmann::json& machine) {
  if (!machine.is_object() || !machine.contains("cores") || !machine["cores"].is_number_integer())
    return -1;
  return machine["cores"].get<long long>();
}

}  // namespace

std::string node_name(const nlohmann::json& machine) {
  return text_field(machine, "hostname", "");
}

nlohmann::json distinct_machines(const nlohmann::json& machines) {
  nlohmann::json out = nlohmann::json::array();
  std::set<std::tuple<std::string, std::string, long long>> seen;
  for (const auto& m : machines)
    if (seen.emplace(node_name(m), text_field(m, "cpu_model", "unknown"), cores_field(m)).second)
      out.push_back(m);
  return out;
}

nlohmann::json mixed_hardware(const nlohmann::json& machines) {
  std::vector<std::string> models;
  std::vector<long long> cores;
  for (const auto& m : machines) {
    const std::string model = text_field(m, "cpu_model", "unknown");
    const long long n = cores_field(m);
    if (std::find(models.begin(), models.end(), model) == models.end()) models.push_back(model);
    if (std::find(cores.begin(), cores.end(), n) == cores.end()) cores.push_back(n);
  }
  if (models.size() < 2 && cores.size() < 2) return nullptr;
  std::string list_models, list_cores;
  for (const auto& m : models) list_models += (list_models.empty() ? "" : "; ") + m;
  for (const auto n : cores) list_cores += (list_cores.empty() ? "" : ", ") + std::to_string(n);
  return {{"cpu_models", models},
          {"cores", cores},
          {"warning", "rows were measured on different hardware (CPU models: " + list_models +
                          "; core counts: " + list_cores +
                          "): compare render times and speedups only between rows of one machine "
                          "(each row's node; merged_from and machines give each node's CPU)"}};
}

}  // namespace harness
