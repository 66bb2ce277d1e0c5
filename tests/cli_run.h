#pragma once
// Running the accelbench binary from a test as a user runs it, output and exit status captured.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace cli_run {

struct CliRun {
  int status = -1;     ///< Exit status (-1: killed by a signal).
  std::string output;  ///< stdout and stderr together.
};

/// Runs `shell_command` (a command line for /bin/sh) with stderr joined to stdout.
inline CliRun run(const std::string& shell_command) {
  CliRun result;
  FILE* pipe = popen((shell_command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buf;
  while (std::fgets(buf.data(), int(buf.size()), pipe)) result.output += buf.data();
  const int raw = pclose(pipe);
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return result;
}

}  // namespace cli_run
