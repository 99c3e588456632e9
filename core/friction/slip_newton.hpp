// The scalar solve inside a return map (rate_state.cpp, Eqs. 1–4): the slip increment Δλ of a
// slipping step is the root of R(Δλ) = a − k_r Δλ − Y(α(Δλ)) − η t_N Δλ/Δt on a bracket
// [lo, hi] with R(lo) > 0 ≥ R(hi). Newton, safeguarded by bisection inside the bracket, so it
// always converges. One copy, used by RateStateLaw and by identify's ExtendedLaw (whose
// strength carries the effects); each law supplies its own residual.
#pragma once

#include <algorithm>
#include <cmath>

namespace stickslip {

struct SlipRoot {
    double x = 0.0;        // Δλ [m]
    double R = 0.0;        // R(x) [N]
    double dR = 0.0;       // R'(x) [N/m]
    int iterations = 0;    // residual evaluations (ReturnMapResult::iterations)
    bool converged = false;
};

// exp(y), but +0 directly below y = −746, where the correctly rounded exp is +0: glibc's exp
// takes its underflow path there (raising the flag and setting errno), 1.2 % of a whole identify
// of D13 and 3.9 % of its baseline fit (the state's relaxation e^{−Δλ/D_c} over a step that
// slips many D_c).
inline double expOrZero(double y) { return y < -746.0 ? 0.0 : std::exp(y); }

// Whether R(x) < 0 is certain without evaluating R there, for a residual of the form
//   R(x) = a − k x − y0 − c (exp(α(x)/r) − 1),   c ≥ 0,
// given a lower bound uLow ≤ α(x)/r: since exp(u) − 1 ≥ max(−1, u),
//   R(x) ≤ a − k x − y0 − c max(−1, uLow).
// The bound must be below zero by 1e-9 of the terms' size, far beyond the round-off of either
// the bound or an evaluation of R, so a `true` is the sign an evaluation would compute (the
// laws use it to skip the evaluation at the zero-force slip a/ε, bit for bit the same result:
// tst_return_map::zeroForceCheckNeedsNoEvaluationWhenCertain).
inline bool slipResidualCertainlyNegative(double a, double kx, double y0, double c, double uLow) {
    if (!(c >= 0.0) || !std::isfinite(uLow)) return false;
    const double bound = a - kx - y0 - c * std::max(-1.0, uLow);
    const double size = std::abs(a) + std::abs(kx) + std::abs(y0) + c * std::max(1.0, std::abs(uLow));
    return bound < -1e-9 * size;
}

// eval(x, R, dR) evaluates the residual and its slope at x; the caller's functor also keeps
// whatever else it needs of the last point evaluated (α, exp(α/r)), which is the returned x.
// The solve starts from x0 with R(x0) = R0 and R'(x0) = dR0 already known (no evaluation),
// or, when 0 < slipHint < hi, from an evaluation at slipHint (a warm start, e.g. the previous
// step's Δλ in steady sliding), which tightens the bracket before Newton continues from it.
// Stops on |R| ≤ ftol, on a collapsed bracket, or when the iterate no longer moves
// (round-off floor).
template <class Eval>
SlipRoot solveSlip(Eval&& eval, double x0, double R0, double dR0, double lo, double hi, double slipHint, double ftol) {
    SlipRoot r;
    r.x = x0;
    r.R = R0;
    r.dR = dR0;
    int it = 0;
    bool ok = false;
    if (slipHint > 0.0 && slipHint < hi) {
        r.x = slipHint;
        eval(r.x, r.R, r.dR);
        if (r.R > 0.0) lo = r.x; else hi = r.x;
        ++it;
        if (std::abs(r.R) <= ftol) ok = true;
    }
    r.iterations = it;
    for (; !ok && it < 200; ++it) {
        double xn = (r.dR < 0.0) ? r.x - r.R / r.dR : 0.5 * (lo + hi);
        if (!(xn > lo && xn < hi)) xn = 0.5 * (lo + hi);  // bisection safeguard
        const double step = std::abs(xn - r.x);
        r.x = xn;
        eval(r.x, r.R, r.dR);
        ++r.iterations;
        if (r.R > 0.0) lo = r.x; else hi = r.x;
        if (std::abs(r.R) <= ftol || hi - lo <= 1e-15 * hi || step <= 4e-16 * r.x) { ok = true; break; }
    }
    r.converged = ok;
    return r;
}

}  // namespace stickslip
