#include "recipes.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "../dsp/stats.hpp"

namespace stickslip::identify {

PullEstimate muFromPull(const std::vector<double>& V, const std::vector<double>& F, double tN, double tol) {
    PullEstimate e;
    const size_t n = std::min(V.size(), F.size());
    if (n < 4 || !(tN > 0.0) || !(tol > 0.0 && tol < 1.0)) {
        e.message = "need at least 4 samples of velocity and force, t_N > 0 and a tolerance in (0, 1)";
        return e;
    }
    double vmax = 0;
    for (size_t i = 0; i < n; ++i) vmax = std::max(vmax, std::abs(V[i]));
    if (!(vmax > 0)) {
        e.message = "the velocity is zero throughout: no pull";
        return e;
    }
    std::vector<double> fast;
    for (size_t i = 0; i < n; ++i)
        if (std::abs(V[i]) > 0.5 * vmax) fast.push_back(std::abs(V[i]));
    const double plateau = dsp::median(fast);
    size_t bestB = 0, bestE = 0;
    for (size_t i = 0; i < n;) {
        auto inPull = [&](size_t k, double sign) {
            return std::abs(std::abs(V[k]) - plateau) <= tol * plateau && V[k] * sign > 0;
        };
        const double sign = V[i] >= 0 ? 1.0 : -1.0;
        if (!inPull(i, sign)) { ++i; continue; }
        size_t j = i;
        while (j < n && inPull(j, sign)) ++j;
        if (j - i > bestE - bestB) { bestB = i; bestE = j; }
        i = j;
    }
    if (bestE - bestB < 4) {
        e.message = "no stretch of constant velocity found";
        return e;
    }
    e.begin = bestB;
    e.end = bestE;
    e.pullVelocity_mps = plateau;
    e.peakIndex = bestB;
    for (size_t i = bestB; i < bestE; ++i)
        if (std::abs(F[i]) > std::abs(F[e.peakIndex])) e.peakIndex = i;
    e.mu = std::abs(F[e.peakIndex]) / tN;
    std::vector<double> late;
    for (size_t i = bestB + (bestE - bestB) / 2; i < bestE; ++i) late.push_back(std::abs(F[i]) / tN);
    e.kineticRatio = dsp::median(std::move(late));
    e.ok = true;
    return e;
}

ImpulseEstimate etaFromImpulse(const std::vector<double>& V, const std::vector<double>& F, double tN, size_t before,
                               size_t after) {
    ImpulseEstimate e;
    const size_t n = std::min(V.size(), F.size());
    if (n < before + after + 2 || !(tN > 0.0) || before < 1 || after < 1) {
        e.message = "too few samples around the impulse, or t_N <= 0";
        return e;
    }
    size_t best = before;
    double jump = -1;
    for (size_t i = before; i + after < n; ++i) {
        const double d = std::abs(std::abs(V[i + 1]) - std::abs(V[i]));
        if (d > jump) { jump = d; best = i; }
    }
    const size_t a = best + 1 - before, b = best + after;
    e.index = best;
    e.dv_mps = std::abs(V[b]) - std::abs(V[a]);
    e.ds = (std::abs(F[b]) - std::abs(F[a])) / tN;
    if (!(std::abs(e.dv_mps) > 0)) {
        e.message = "no velocity jump found";
        return e;
    }
    e.eta_s_per_m = e.ds / e.dv_mps;
    e.ok = true;
    return e;
}

}  // namespace stickslip::identify
