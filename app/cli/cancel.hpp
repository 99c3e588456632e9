// Ctrl-C / SIGTERM for the long commands: the first signal asks the running job to stop (the
// core polls the flag and returns RunStatus::Cancelled), the command then writes no output
// file and exits with kCancelled; a --checkpoint log keeps the finished items and resumes.
// A second signal ends the process at once (exit 128 + signal): an atomic writer caught in
// the middle leaves only its NAME.tmp.XXXXXX beside the untouched target.
#pragma once

#include <atomic>

namespace stickslip::cli {

// Installs the SIGINT and SIGTERM handlers (main() calls it once, before parsing).
void installCancelHandlers();

// The flag the handlers set; pass its address as RunControl::cancel / FitRequest::cancel.
const std::atomic<bool>& cancelFlag();
inline bool cancelRequested() { return cancelFlag().load(std::memory_order_relaxed); }

}  // namespace stickslip::cli
