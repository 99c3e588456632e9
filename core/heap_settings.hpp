// The process's heap settings for long numerical jobs (identify, fits, sweeps, maps).
#pragma once

#include <cstddef>

namespace stickslip {

struct HeapSettings {
    std::size_t mmapThreshold_bytes = std::size_t{32} << 20;
    std::size_t trimThreshold_bytes = std::size_t{128} << 20;
};

// glibc's malloc serves a block above its mmap threshold (128 KiB at first) with a fresh mapping
// and returns the heap's free top to the system whenever it passes the trim threshold, so the
// run-length buffers a fit allocates and frees thousands of times (law runs, filtered
// predictions, residual vectors) are faulted in anew each time. With both thresholds raised they
// are reused. Measured on D05 (stickslip-cli identify, idle, back to back): system time 2.5–3.7 s
// → 0.55 s, wall 26.5–29.5 s → 23.3 s, peak RSS 154 → 164 MB; the report identical. Call once at
// the start of main(), before threads start. False where the C library has no such settings (not
// glibc, or AddressSanitizer's allocator) or a value does not fit mallopt's int.
bool applyHeapSettings(const HeapSettings& s = {});

}  // namespace stickslip
