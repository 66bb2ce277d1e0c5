#pragma once
// The subcommands of `accelbench`, one file each. Every add_*_command() registers its
// subcommand on `app`; its callback runs after parsing and stores the process exit status in
// `exit_code`. A failure is thrown as an exception whose what() is one line: main() prints it as
// `accelbench: <message>` and exits with status 1.

#include <CLI/CLI.hpp>

#include <cstddef>
#include <functional>

namespace cli {

/// What a caller of run() may inject (the tests); main() injects nothing.
struct Hooks {
  /// Passed to harness::RunOptions::after_row of `sweep`: called after each row it writes.
  std::function<void(std::size_t rows_written)> after_sweep_row;
};

/// The whole command line: parses argv, runs the subcommand and returns the exit status; a
/// failure is one line on stderr, `accelbench: <message>`.
int run(int argc, char** argv, const Hooks& hooks = {});


void add_render_command(CLI::App& app, int& exit_code);
void add_gen_command(CLI::App& app, int& exit_code);
void add_sweep_command(CLI::App& app, int& exit_code, const Hooks& hooks = {});
void add_tune_command(CLI::App& app, int& exit_code);
void add_merge_command(CLI::App& app, int& exit_code);
void add_convert_command(CLI::App& app, int& exit_code);
void add_fronts_command(CLI::App& app, int& exit_code);
void add_structures_command(CLI::App& app, int& exit_code);
void add_integrators_command(CLI::App& app, int& exit_code);
void add_stability_command(CLI::App& app, int& exit_code);

}  // namespace cli
