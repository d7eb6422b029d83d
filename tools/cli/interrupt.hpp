#pragma once
// Ctrl-C (and SIGTERM) for long runs: the handler only raises a flag, which the job checks between
// steps, so it can write its checkpoint and stop cleanly.
#include <atomic>

namespace vksplat::cli {

// Installs the handlers (again on each call, which is harmless) and returns the flag they raise. A signal handler can only reach a
// flag with static storage, so this is the one such flag of the program.
const std::atomic<bool>& stop_on_interrupt();

}  // namespace vksplat::cli
