#include "interrupt.hpp"

#include <csignal>

namespace vksplat::cli {
namespace {

std::atomic<bool> stop_requested{false};

extern "C" void raise_stop_flag(int) { stop_requested.store(true); }

}  // namespace

const std::atomic<bool>& stop_on_interrupt() {
    std::signal(SIGINT, raise_stop_flag);
    std::signal(SIGTERM, raise_stop_flag);
    return stop_requested;
}

}  // namespace vksplat::cli
