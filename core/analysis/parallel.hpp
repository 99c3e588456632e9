// Deterministic parallel loop for the analyses: indices are handed out one at a time from
// an atomic counter; every index writes only its own output slot, so results do not depend
// on the thread count or the order of completion.
#pragma once

#include <cstddef>
#include <functional>

namespace stickslip {

// Number of worker threads for `requested` (0 = hardware concurrency, at least 1), capped at n.
int workerCount(int requested, std::size_t n);

// Runs body(i) for i in [0, n) on `threads` threads (0 = all). body must be thread-safe
// across distinct i. stop() is polled before every index; when it returns true no new
// indices are started.
void parallelFor(std::size_t n, int threads, const std::function<void(std::size_t)>& body,
                 const std::function<bool()>& stop = {});

// parallelFor that reports each finished index: after body(i), done(i) and then
// progress(finished / n) run under one lock (either may be empty), so callers need no locking
// of their own to stream results (e.g. to rank 0 of an MPI job or a checkpoint).
void parallelForReporting(std::size_t n, int threads, const std::function<void(std::size_t)>& body,
                          const std::function<void(std::size_t)>& done, const std::function<void(double)>& progress,
                          const std::function<bool()>& stop = {});

}  // namespace stickslip
