#pragma once
// Clean stop on SIGINT/SIGTERM: the first signal asks the sweep to stop after the configuration
// it is measuring (and write its results); a second one ends the process at once.

namespace harness {

/// Installs the SIGINT and SIGTERM handlers (idempotent) and clears any earlier request.
void install_stop_handlers();

/// True once SIGINT or SIGTERM has arrived since install_stop_handlers().
bool stop_requested();

/// The signal number that asked to stop, or 0.
int stop_signal();

}  // namespace harness
