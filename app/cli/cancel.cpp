#include "cancel.hpp"

#include <csignal>
#include <unistd.h>

namespace stickslip::cli {

namespace {

std::atomic<bool> gCancel{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the flag is set from a signal handler");

extern "C" void onCancelSignal(int sig) {
    // Only async-signal-safe calls here: an atomic store, write(2) and _exit(2).
    if (gCancel.exchange(true)) {
        constexpr char msg[] = "\nstickslip-cli: second signal, stopping now\n";
        [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, msg, sizeof msg - 1);
        ::_exit(128 + sig);
    }
    constexpr char msg[] = "\nstickslip-cli: cancelling (signal again to stop at once)\n";
    [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, msg, sizeof msg - 1);
}

}  // namespace

void installCancelHandlers() {
    struct sigaction sa {};
    sa.sa_handler = onCancelSignal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;  // the job's reads and writes carry on; the flag is polled
    ::sigaction(SIGINT, &sa, nullptr);
    ::sigaction(SIGTERM, &sa, nullptr);
}

const std::atomic<bool>& cancelFlag() { return gCancel; }

}  // namespace stickslip::cli
