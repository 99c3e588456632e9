#include "rate_state.hpp"

#include <algorithm>
#include <cmath>

namespace stickslip {

double RateStateLaw::K1(double alpha) const { return params.C1 * (std::exp(alpha / params.r) - 1.0); }

double RateStateLaw::slipFunction(const LawState& s, double tN) const {
    return std::abs(s.force_N) - tN * (params.mu + K1(s.alpha));
}

double RateStateLaw::steadyStateAlpha(double v) const { return -params.C2() * std::abs(v); }

double RateStateLaw::steadyStateRatio(double v) const {
    return params.mu + K1(steadyStateAlpha(v)) + params.eta_s_per_m * std::abs(v);
}

// Return mapping (backward Euler on λ and α, as in computational plasticity).
//
// Elastic predictor:  F_tr = F_n + ε Δg,  a = |F_tr|,  s = sign F_tr,
//                     Φ_tr = a − t_N (μ + K1(α_n)).
// If Φ_tr ≤ 0 the step is elastic (stick): F = F_tr, α = α_n, dF/dΔg = ε.
// Otherwise, with the unknown slip increment Δλ > 0 (radial return keeps s):
//   F_{n+1}  = s (a − ε Δλ)                                       (4), BE
//   α_{n+1}  = (α_n − C2 Δλ²/(D_c Δt)) / (1 + Δλ/D_c)              (2), BE with λ̇ = Δλ/Δt
//   Φ_{n+1}  = η t_N Δλ/Δt                                          (3)
// so Δλ is the root of the scalar residual
//   R(Δλ) = a − ε Δλ − t_N (μ + K1(α_{n+1}(Δλ))) − η t_N Δλ/Δt.
// R(0) = Φ_tr > 0 and, because K1 ≥ −C1,
//   R(Δλ) ≤ Φ_tr + t_N (K1(α_n) + C1) − (ε + η t_N/Δt) Δλ,
// so [0, Δλ_max] with Δλ_max = (Φ_tr + t_N(K1(α_n)+C1)) / (ε + η t_N/Δt) brackets a root.
// We solve by Newton safeguarded with bisection inside the bracket: it always converges.
//
// Consistent tangent: R depends on Δg only through a (∂R/∂a = 1, ∂a/∂Δg = s ε), hence
//   dΔλ/dΔg = −s ε / R',  dF/dΔg = s (s ε − ε dΔλ/dΔg) = ε (1 + ε/R'),
// with R' = dR/dΔλ = −ε − η t_N/Δt − t_N K1'(α) dα/dΔλ.
ReturnMapResult RateStateLaw::returnMap(const LawState& st, double dg, double dt, double tN) const {
    const RateStateParams& p = params;
    const double eps = p.epsT_N_per_m;
    ReturnMapResult res;
    const double trial = st.force_N + eps * dg;
    const double a = std::abs(trial);
    const double phiTrial = a - tN * (p.mu + K1(st.alpha));
    if (phiTrial <= 0.0) {
        res.state = {trial, st.alpha};
        res.tangent_N_per_m = eps;
        res.stuck = true;
        return res;
    }
    res.stuck = false;
    const double s = trial >= 0.0 ? 1.0 : -1.0;
    const double C2 = p.C2();
    const double invDc = 1.0 / p.Dc_m;
    const double visc = p.eta_s_per_m * tN / dt;   // η t_N / Δt  [N/m]
    const double c2q = C2 * invDc / dt;            // C2 / (D_c Δt) [1/m²]
    const double invR = 1.0 / p.r;

    // Residual and derivative at Δλ = x; also returns α(x).
    auto eval = [&](double x, double& R, double& dR, double& alpha) {
        const double num = st.alpha - c2q * x * x;
        const double den = 1.0 + x * invDc;
        alpha = num / den;
        const double dalpha = (-2.0 * c2q * x - alpha * invDc) / den;
        const double e = std::exp(alpha * invR);
        R = a - eps * x - tN * (p.mu + p.C1 * (e - 1.0)) - visc * x;
        dR = -eps - visc - tN * p.C1 * invR * e * dalpha;
    };

    double lo = 0.0;
    double hi = (phiTrial + tN * (K1(st.alpha) + p.C1)) / (eps + visc);
    double R = 0, dR = 0, alpha = st.alpha;
    // Keep the force from changing sign (possible only when C1 > μ at extreme rates).
    if (hi * eps > a) {
        eval(a / eps, R, dR, alpha);
        if (R > 0.0) {
            res.state = {0.0, alpha};
            res.slipIncrement_m = a / eps;
            res.tangent_N_per_m = 0.0;
            return res;
        }
        hi = a / eps;
    }

    // Newton from the linearised first guess (exact when K1 is constant).
    double x = phiTrial / (eps + visc);
    if (x > hi) x = 0.5 * (lo + hi);
    const double ftol = 1e-13 * (a + tN);
    const double xtol = 1e-15 * hi + 1e-300;
    int it = 0;
    bool ok = false;
    for (; it < 200; ++it) {
        eval(x, R, dR, alpha);
        if (std::abs(R) <= ftol) { ok = true; break; }
        if (R > 0.0) lo = x; else hi = x;
        double xn = (dR < 0.0) ? x - R / dR : 0.5 * (lo + hi);
        if (!(xn > lo && xn < hi)) xn = 0.5 * (lo + hi);  // bisection safeguard
        if (std::abs(xn - x) <= xtol || hi - lo <= xtol) { x = xn; eval(x, R, dR, alpha); ok = true; break; }
        x = xn;
    }
    res.iterations = it + 1;
    res.converged = ok;
    res.slipIncrement_m = x;
    res.state = {s * (a - eps * x), alpha};
    res.tangent_N_per_m = (dR < 0.0) ? eps * (1.0 + eps / dR) : 0.0;
    return res;
}

}  // namespace stickslip
