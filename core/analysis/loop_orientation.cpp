#include "loop_orientation.hpp"

#include <algorithm>
#include <cmath>

namespace stickslip {

LoopOrientation frictionLoopOrientation(const std::vector<double>& t, const std::vector<double>& V,
                                        const std::vector<double>& rho, double period_s, double degenerateFraction) {
    LoopOrientation out;
    const std::size_t n = std::min({t.size(), V.size(), rho.size()});
    if (n < 3 || !(period_s > 0)) return out;
    std::size_t start = 0;
    const double t0 = t.front();
    for (long cycle = 1;; ++cycle) {
        const double tEnd = t0 + static_cast<double>(cycle) * period_s;
        // The cycle covers samples [start, end): all samples with t < tEnd (tolerant of rounding).
        std::size_t end = start;
        const double eps = 1e-9 * period_s;
        while (end < n && t[end] < tEnd - eps) ++end;
        if (end >= n) break;  // incomplete last cycle
        if (end - start >= 3) {
            double area = 0, vmin = V[start], vmax = V[start], rmin = rho[start], rmax = rho[start];
            for (std::size_t i = start; i < end; ++i) {
                const std::size_t j = (i + 1 < end) ? i + 1 : start;  // close the loop
                area += V[i] * rho[j] - V[j] * rho[i];
                vmin = std::min(vmin, V[i]); vmax = std::max(vmax, V[i]);
                rmin = std::min(rmin, rho[i]); rmax = std::max(rmax, rho[i]);
            }
            area *= 0.5;
            out.cycleStart_s.push_back(t[start]);
            out.signedArea.push_back(area);
            const double box = (vmax - vmin) * (rmax - rmin);
            if (!(std::abs(area) > degenerateFraction * box) || box == 0) ++out.degenerate;
            else if (area > 0) ++out.counterClockwise;
            else ++out.clockwise;
        }
        start = end;
    }
    return out;
}

}  // namespace stickslip
