#include "heap_settings.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <climits>

namespace stickslip {

bool applyHeapSettings(const HeapSettings& s) {
#if defined(__GLIBC__)
    if (s.mmapThreshold_bytes > static_cast<std::size_t>(INT_MAX) || s.trimThreshold_bytes > static_cast<std::size_t>(INT_MAX))
        return false;
    // mallopt returns 1 on success.
    const bool mmapOk = mallopt(M_MMAP_THRESHOLD, static_cast<int>(s.mmapThreshold_bytes)) == 1;
    const bool trimOk = mallopt(M_TRIM_THRESHOLD, static_cast<int>(s.trimThreshold_bytes)) == 1;
    return mmapOk && trimOk;
#else
    (void)s;
    return false;
#endif
}

}  // namespace stickslip
