#pragma once
// Keeping a one-thread measurement on one CPU.

namespace harness {

/// Binds the calling thread, and the threads it starts afterwards, to the CPU it runs on now, so
/// that the scheduler cannot move a one-thread measurement between CPUs whose host threads are
/// not equally busy (docs/sweeps.md, "Pinning a one-thread sweep to one CPU"). Returns that CPU,
/// or -1 when it could not pin (the thread then stays free to move).
int pin_to_current_cpu();

}  // namespace harness
