// The accelbench command line as a function: every subcommand registered, argv parsed, one
// line on stderr for any failure (main.cpp calls it; tests call it in a forked child).

#include "cli/commands.h"

#include "input/message.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <iostream>
#include <new>
#include <string>

namespace cli {

namespace {

/// The message on one line of about 200 characters at most, whatever the exception put in it.
std::string one_line(const std::string& s) { return input::one_line(s); }

}  // namespace

int run(int argc, char** argv, const Hooks& hooks) {
  CLI::App app{"Benchmark harness for ray-tracing acceleration structures.", "accelbench"};
  app.require_subcommand(1);
  app.failure_message(CLI::FailureMessage::simple);
  int exit_code = 0;
  add_render_command(app, exit_code);
  add_gen_command(app, exit_code);
  add_sweep_command(app, exit_code, hooks);
  add_tune_command(app, exit_code);
  add_merge_command(app, exit_code);
  add_convert_command(app, exit_code);
  add_fronts_command(app, exit_code);
  add_structures_command(app, exit_code);
  add_integrators_command(app, exit_code);
  add_stability_command(app, exit_code);
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

}  // namespace cli
