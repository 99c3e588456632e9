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

namespace {

void closeLoop(const std::vector<double>& t, const std::vector<double>& V, const std::vector<double>& rho,
               std::size_t b, std::size_t e, double vmaxAll, const LoopOptions& opt, FrictionLoops& out) {
    if (e <= b) return;
    double peak = 0;
    for (std::size_t i = b; i < e; ++i) peak = std::max(peak, std::abs(V[i]));
    if (!(peak > opt.minPeakFraction * vmaxAll)) return;
    std::vector<std::size_t> keep;
    for (std::size_t i = b; i < e; ++i)
        if (std::abs(V[i]) >= opt.minSpeedFraction * peak) keep.push_back(i);
    if (keep.size() < 3) return;
    double area = 0, vmin = V[keep[0]], vmax = vmin, rmin = rho[keep[0]], rmax = rmin;
    for (std::size_t k = 0; k < keep.size(); ++k) {
        const std::size_t i = keep[k], j = keep[(k + 1) % keep.size()];  // last → first: the chord
        area += V[i] * rho[j] - V[j] * rho[i];
        vmin = std::min(vmin, V[i]); vmax = std::max(vmax, V[i]);
        rmin = std::min(rmin, rho[i]); rmax = std::max(rmax, rho[i]);
    }
    area *= 0.5;
    out.start_s.push_back(t[b]);
    out.signedArea.push_back(area);
    out.sign.push_back(V[keep[0]] > 0 ? 1 : -1);
    const double box = (vmax - vmin) * (rmax - rmin);
    if (box == 0 || !(std::abs(area) > opt.degenerateFraction * box)) ++out.degenerate;
    else if (area > 0) ++out.counterClockwise;
    else ++out.clockwise;
}

}  // namespace

FrictionLoops frictionLoops(const std::vector<double>& t, const std::vector<double>& V, const std::vector<double>& rho,
                            const LoopOptions& opt) {
    FrictionLoops out;
    const std::size_t n = std::min({t.size(), V.size(), rho.size()});
    if (n < 3) return out;
    double vmaxAll = 0;
    for (std::size_t i = 0; i < n; ++i) vmaxAll = std::max(vmaxAll, std::abs(V[i]));
    if (!(vmaxAll > 0)) return out;
    // Excursions: maximal runs of one sign of V (zeros end a run). The first and last runs
    // may be cut by the record's ends: they are left out.
    auto sgn = [](double v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); };
    std::size_t b = 0;
    while (b < n && sgn(V[b]) == sgn(V[0])) ++b;  // skip the (possibly partial) first run
    while (b < n) {
        while (b < n && sgn(V[b]) == 0) ++b;
        if (b >= n) break;
        std::size_t e = b;
        while (e < n && sgn(V[e]) == sgn(V[b])) ++e;
        if (e >= n) break;  // partial last run
        closeLoop(t, V, rho, b, e, vmaxAll, opt, out);
        b = e;
    }
    return out;
}

}  // namespace stickslip
