#include "harness/sweep_interrupt.h"

#include <csignal>

namespace harness {
namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_stop_signal(int sig) {
  g_signal = sig;
  // Restore the default action: a second Ctrl-C kills the process at once.
  std::signal(sig, SIG_DFL);
}

}  // namespace

void install_stop_handlers() {
  g_signal = 0;
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
}

bool stop_requested() { return g_signal != 0; }

int stop_signal() { return g_signal; }

}  // namespace harness
