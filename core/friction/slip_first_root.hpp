// The first root of a return map's slip residual (Eqs. 1–4),
//   R(Δλ) = a − k Δλ − y0 − P r (exp(α(Δλ)/r) − 1),   k = ε + η t_N/Δt,  P = t_N C1 / r,
// whose slope is R' = −k − P exp(α/r) α'. When the state's weakening can outrun the spring
// (P exp(α/r)(−α') > k somewhere, a slip of many D_c in one step), R can have three roots and a
// Newton solve from the elastic predictor may return the third. The step's continuation from
// Δλ = 0, the solution that the small-step limit follows, is the first one. This file gives
// rigorous bounds of R' over an interval, without evaluating R, and a search that keeps the
// first root inside its bracket by certifying every point it moves the lower end to.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "slip_newton.hpp"

namespace stickslip {

// The state's form over a slipping step (Eq. 2's two discretisations, c = C2/Δt, y = Δλ/D_c):
//   constant rate:   α = (α_n + c Δλ) e^{−y} − c Δλ,   α' = −c (1 − e^{−y}(1 − y)) − (α_n/D_c) e^{−y};
//   backward Euler:  α = (α_n − c D_c y²)/(1 + y),     α' = −c (1 − z) − (α_n/D_c) z,  z = 1/(1 + y)².
struct SlipShape {
    bool constantRate = false;
    double alpha0 = 0;  // α_n
    double c = 0;       // C2/Δt [1/m], ≥ 0
    double invDc = 1;   // 1/D_c [1/m]
    double invR = 1;    // 1/r
    double P = 0;       // t_N C1_eff / r [N]: the weakening's factor in R'
    double k = 0;       // ε + η t_N/Δt [N/m]
};

struct SlopeRange {
    double min = 0, max = 0;  // bounds of R' over the interval [N/m]
};

// R' = −k − P e α' for e ∈ [e1, e2] (e ≥ 0) and α' ∈ [d1, d2]: interval arithmetic.
inline SlopeRange slopeFromRanges(const SlipShape& s, double e1, double e2, double d1, double d2) {
    const double p[4] = {e1 * d1, e1 * d2, e2 * d1, e2 * d2};
    const double lo = std::min(std::min(p[0], p[1]), std::min(p[2], p[3]));
    const double hi = std::max(std::max(p[0], p[1]), std::max(p[2], p[3]));
    const double a = -s.P * lo, b = -s.P * hi;
    return {-s.k + std::min(a, b), -s.k + std::max(a, b)};
}

// Bounds of R' over every Δλ ≥ 0, without an exponential (every slipping step asks this):
// α ≤ max(α_n, 0) in both steps, so exp(α/r) ∈ [0, eMax] with eMax = exp(max(α_n, 0)/r)
// (expAlpha0 = exp(α_n/r) is at hand); e^{−y}(1 − y) ∈ [−e^{−2}, 1], z ∈ (0, 1].
inline SlopeRange slopeRangeEverywhere(const SlipShape& s, double expAlpha0) {
    const double eMax = s.alpha0 > 0.0 ? expAlpha0 : 1.0;
    const double a0 = -s.alpha0 * s.invDc;
    double d1, d2;
    if (s.constantRate) {
        d1 = -s.c * (1.0 + std::exp(-2.0)) + std::min(0.0, a0);
        d2 = std::max(0.0, a0);
    } else {
        d1 = std::min(-s.c, a0);
        d2 = std::max(-s.c, a0);
    }
    return slopeFromRanges(s, 0.0, eMax, d1, d2);
}

// Bounds of R' over [l, h] (0 ≤ l ≤ h); tight as h − l → 0, so the search below can always
// certify a short enough interval next to a point where R > 0.
inline SlopeRange slopeRangeOn(const SlipShape& s, double l, double h) {
    const double yl = l * s.invDc, yh = h * s.invDc, a0 = s.alpha0 * s.invDc;
    double al1, al2, d1, d2;  // α and α' over [l, h]
    if (s.constantRate) {
        const double El = expOrZero(-yl), Eh = expOrZero(-yh);
        al1 = std::min(s.alpha0 * El, s.alpha0 * Eh) - s.c * h * (1.0 - Eh);
        al2 = std::max(s.alpha0 * El, s.alpha0 * Eh) - s.c * l * (1.0 - El);
        // g = e^{−y}(1 − y) falls to its minimum −e^{−2} at y = 2 and rises after.
        const double gl = El * (1.0 - yl), gh = Eh * (1.0 - yh);
        const double gMin = (yl <= 2.0 && yh >= 2.0) ? -std::exp(-2.0) : std::min(gl, gh);
        const double gMax = std::max(gl, gh);
        d1 = -s.c * (1.0 - gMin) + std::min(-a0 * El, -a0 * Eh);
        d2 = -s.c * (1.0 - gMax) + std::max(-a0 * El, -a0 * Eh);
    } else {
        const double Dc = 1.0 / s.invDc;
        const double ql = 1.0 / (1.0 + yl), qh = 1.0 / (1.0 + yh);  // 1/(1 + y), falling
        // α = α_n/(1 + y) − c D_c y²/(1 + y), the second term falling in y.
        al1 = std::min(s.alpha0 * ql, s.alpha0 * qh) - s.c * Dc * yh * yh * qh;
        al2 = std::max(s.alpha0 * ql, s.alpha0 * qh) - s.c * Dc * yl * yl * ql;
        const double zl = ql * ql, zh = qh * qh;  // α' is linear in z
        const double dl = -s.c * (1.0 - zl) - a0 * zl, dh = -s.c * (1.0 - zh) - a0 * zh;
        d1 = std::min(dl, dh);
        d2 = std::max(dl, dh);
    }
    return slopeFromRanges(s, expOrZero(al1 * s.invR), std::exp(std::min(al2 * s.invR, 700.0)), d1, d2);
}

// The first root of R on (lo, hi], given R > 0 on [0, lo] with R(lo) = R0, R'(lo) = dR0, and
// R(hi) ≤ 0. Invariant: every point the lower end moves to is certified, i.e. R > 0 on the
// whole step from the old lower end (R' bounds from slopeRangeOn, from both ends); a point with
// R ≤ 0 becomes the upper end. Once R' < 0 is certain on [lo, hi] the root there is the only
// one, and the ordinary solve finishes. As solveSlip: the last point evaluated is the returned x.
template <class Eval>
SlipRoot solveFirstSlip(Eval&& eval, const SlipShape& shape, double R0, double dR0, double lo, double hi, double ftol) {
    double Rlo = R0, dRlo = dR0, probe = hi;
    double lastX = std::numeric_limits<double>::quiet_NaN(), lastR = 0, lastDR = 0;
    int evaluations = 0;
    auto evalAt = [&](double x, double& R, double& dR) {
        eval(x, R, dR);
        ++evaluations;
        lastX = x, lastR = R, lastDR = dR;
    };
    auto finish = [&](double x, bool converged) {
        SlipRoot r;
        if (!(x == lastX)) evalAt(x, r.R, r.dR);
        r.x = x, r.R = lastR, r.dR = lastDR, r.iterations = evaluations, r.converged = converged;
        return r;
    };
    while (evaluations < 400) {
        if (hi - lo <= 1e-15 * hi) return finish(hi, true);
        if (slopeRangeOn(shape, lo, hi).max < 0.0) {  // one root in (lo, hi]
            SlipRoot r = solveSlip(eval, lo, Rlo, dRlo, lo, hi, 0.0, ftol);
            r.iterations += evaluations;
            return r;
        }
        double m = dRlo < 0.0 ? lo - Rlo / dRlo : 0.5 * (lo + probe);
        if (!(m > lo && m < probe)) m = 0.5 * (lo + probe);
        double Rm = 0, dRm = 0;
        evalAt(m, Rm, dRm);
        if (Rm <= 0.0) {
            hi = probe = m;
            continue;
        }
        // R > 0 on [lo, m]? R ≥ R(lo) + min R' (x − lo) from the left, R ≥ R(m) − max R' (m − x) from the right.
        const SlopeRange t = slopeRangeOn(shape, lo, m);
        const double leftReach = t.min >= 0.0 ? m : lo + Rlo / -t.min;
        const double rightReach = t.max <= 0.0 ? lo : m - Rm / t.max;
        if (leftReach > rightReach) {
            lo = m, Rlo = Rm, dRlo = dRm, probe = hi;
            if (Rlo <= ftol) return finish(lo, true);
        } else {
            probe = m;  // look closer to lo, where the left bound reaches
        }
    }
    return finish(hi, false);
}

// The return maps' slip solve: the ordinary solve from Δλ = 0 (its warm start slipHint, as
// solveSlip), kept as it is when its root is certainly the first one, i.e. R' < 0 on [0, hi] by
// the bound without an exponential, or on [0, root] (then R > 0 before the root, as R(0) > 0);
// otherwise the certified search, on [0, root] when R(root) ≤ 0. So the result is the ordinary
// solve's bit for bit wherever that is the first root and can be shown to be.
template <class Eval>
SlipRoot solveSlipFirstRoot(Eval&& eval, const SlipShape& shape, double expAlpha0, double R0, double dR0, double hi,
                            double slipHint, double ftol) {
    const bool oneRoot = slopeRangeEverywhere(shape, expAlpha0).max < 0.0;
    const SlipRoot r = solveSlip(eval, 0.0, R0, dR0, 0.0, hi, slipHint, ftol);
    if (oneRoot || slopeRangeOn(shape, 0.0, r.x).max < 0.0) return r;
    SlipRoot f = solveFirstSlip(eval, shape, R0, dR0, 0.0, r.R <= 0.0 ? r.x : hi, ftol);
    f.iterations += r.iterations;
    return f;
}

}  // namespace stickslip
