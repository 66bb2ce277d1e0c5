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

/// Runs `shell_command` (a command line for /bin/sh), its stderr joined to stdout unless
/// `join_stderr` is false (then stderr goes to the test's own).
inline CliRun run(const std::string& shell_command, bool join_stderr = true) {
  CliRun result;
  FILE* pipe = popen((shell_command + (join_stderr ? " 2>&1" : "")).c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buf;
  while (std::fgets(buf.data(), int(buf.size()), pipe)) result.output += buf.data();
  const int raw = pclose(pipe);
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return result;
}

#ifdef ACCELBENCH_CLI
/// Runs the accelbench binary under test with `args` (one string, quoted as for /bin/sh).
inline CliRun accelbench(const std::string& args) { return run(std::string(ACCELBENCH_CLI) + " " + args); }
#endif

}  // namespace cli_run
