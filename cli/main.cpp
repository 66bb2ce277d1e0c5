// accelbench: ray-tracing acceleration structures, built, rendered through and measured.

#include "cli/commands.h"

#include "input/message.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <iostream>
#include <new>
#include <string>

namespace {

/// The message on one line of about 200 characters at most, whatever the exception put in it.
std::string one_line(const std::string& s) { return input::one_line(s); }

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Benchmark harness for ray-tracing acceleration structures.", "accelbench"};
  app.require_subcommand(1);
  app.failure_message(CLI::FailureMessage::simple);
  int exit_code = 0;
  cli::add_render_command(app, exit_code);
  cli::add_gen_command(app, exit_code);
  cli::add_sweep_command(app, exit_code);
  cli::add_tune_command(app, exit_code);
  cli::add_merge_command(app, exit_code);
  cli::add_convert_command(app, exit_code);
  cli::add_fronts_command(app, exit_code);
  cli::add_structures_command(app, exit_code);
  cli::add_integrators_command(app, exit_code);
  cli::add_stability_command(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    std::fflush(stdout);  // what the command printed before failing comes first
    std::cerr << "accelbench: " << one_line(e.what()) << " (see --help)\n";
    return e.get_exit_code();
  } catch (const std::bad_alloc&) {
    std::fflush(stdout);
    std::cerr << "accelbench: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::fflush(stdout);
    std::cerr << "accelbench: " << one_line(e.what()) << '\n';
    return 1;
  } catch (...) {
    std::cerr << "accelbench: unexpected error\n";
    return 1;
  }
  return exit_code;
}
