#include "dieterich_ruina.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stickslip {

std::vector<ParamDef> DieterichRuinaLaw::paramRows() {
    using G = ParamGroup;
    return {
        {.key = "mu"},
        {.key = "a", .label = "a", .quantity = "dimensionless", .doc = "Direct-effect coefficient (Dieterich–Ruina)",
         .group = G::FrictionLaw, .lower = 0, .lowerOpen = true, .fit = {1e-4, 1.0, true}, .sliderMin = 0.001,
         .sliderMax = 0.1, .logSlider = true, .decimals = 4},
        {.key = "b", .label = "b", .quantity = "dimensionless", .doc = "Evolution-effect coefficient (Dieterich–Ruina)",
         .group = G::FrictionLaw, .lower = 0, .fit = {0.0, 1.0, false}, .sliderMin = 0.0, .sliderMax = 0.1, .decimals = 4},
        {.key = "Dc"},
        {.key = "V0", .label = "V0", .unit = "m/s", .quantity = "a velocity",
         .doc = "Reference velocity of μ0 (Dieterich–Ruina)", .group = G::FrictionLaw, .lower = 0, .lowerOpen = true,
         .fit = {1e-9, 10.0, true}, .displayUnit = "mm/s", .displayScale = 1e3, .sliderMin = 1e-3, .sliderMax = 100.0,
         .logSlider = true, .decimals = 4},
        {.key = "epsT"},
    };
}

double* DieterichRuinaLaw::field(Params& p, std::string_view key) {
    if (key == "mu") return &p.mu;
    if (key == "a") return &p.a;
    if (key == "b") return &p.b;
    if (key == "Dc") return &p.Dc_m;
    if (key == "V0") return &p.V0_mps;
    if (key == "epsT") return &p.epsT_N_per_m;
    return nullptr;
}

ParamIssues DieterichRuinaParams::validate() const {
    ParamIssues out;
    for (const char* k : {"mu", "a", "b", "Dc", "V0", "epsT"})
        checkParam(k, *DieterichRuinaLaw::field(const_cast<DieterichRuinaParams&>(*this), k), out);
    return out;
}

namespace {

// asinh(e^u) without overflow: u + ln 2 + e^{-2u}/4 − … for large u.
double asinhExp(double u) {
    if (u > 18.0) return u + std::numbers::ln2 + 0.25 * std::exp(-2.0 * u);
    return std::asinh(std::exp(u));
}
// d asinh(e^u)/du = 1/sqrt(1 + e^{-2u}).
double asinhExpSlope(double u) { return u < -300.0 ? std::exp(u) : 1.0 / std::sqrt(1.0 + std::exp(-2.0 * u)); }

}  // namespace

double DieterichRuinaLaw::strengthRatio(double v, double alpha) const {
    const Params& p = params;
    const double av = std::max(std::abs(v), 1e-300);
    return p.a * asinhExp(std::log(av / (2.0 * p.V0_mps)) + (p.mu + p.b * alpha) / p.a);
}

double DieterichRuinaLaw::slipFunction(const LawState& s, double tN) const {
    return std::abs(s.force_N) - tN * strengthRatio(kStickVelocity, s.alpha);
}

double DieterichRuinaLaw::steadyStateAlpha(double v) const {
    return std::log(params.V0_mps / std::max(std::abs(v), 1e-300));
}

double DieterichRuinaLaw::steadyStateRatio(double v) const { return strengthRatio(v, steadyStateAlpha(v)); }

// Return mapping, backward Euler on the slip λ and the aging law (k_r = ε_T for the bare law,
// ε_T K/(K+ε_T) in series with a structure, as for the rate-state law):
//   A = |F_tr|, s = sign F_tr,  F_{n+1} = s (A − k_r Δλ)
//   θ_{n+1} = (θ_n + Δt)/(1 + Δλ/L)  ⇒  α_{n+1} = ln(e^{α_n} + V0 Δt/L) − ln(1 + Δλ/L)
//   A − k_r Δλ = a t_N asinh(Δλ/(2 V0 Δt) exp((μ0 + b α_{n+1})/a)).
// The slip increment spans decades (creep 1e-20 m, slip 1e-5 m), so the unknown is w = ln Δλ:
//   R(w) = a t_N asinh(e^u) − A + k_r e^w,  u = w − ln(2 V0 Δt) + (μ0 + b α_{n+1})/a.
// R → −A < 0 as w → −∞ and R(ln(A/k_r)) > 0, so the root is bracketed; Newton is safeguarded by
// bisection. In creep R is nearly linear in w (asinh ≈ log), in slip k_r e^w dominates.
// Consistent tangent: ∂R/∂A = −1, dA/dΔg = s ε_T ⇒ dF/dΔg = ε_T (1 − k_r Δλ / R_w).
ReturnMapResult DieterichRuinaLaw::Prepared::returnMapFromTrial(const LawState& st, double trial, double slipHint) const {
    ReturnMapResult res;
    res.state = st;
    const double A = std::abs(trial), s = trial >= 0.0 ? 1.0 : -1.0;
    const double alphaAged = std::log(std::exp(st.alpha) + V0 * dt / L);  // α after Δt of healing, no slip
    if (!(A > 0.0)) {
        res.state.force_N = trial;
        res.state.alpha = alphaAged;
        res.tangent_N_per_m = epsT;
        return res;
    }
    const double logScale = std::log(2.0 * V0 * dt);
    const double aTN = a * tN;
    double alpha = alphaAged, Rw = 1.0;
    auto eval = [&](double w) {
        const double dl = std::exp(w);
        alpha = alphaAged - std::log1p(dl / L);
        const double u = w - logScale + (mu + b * alpha) / a;
        const double dudw = 1.0 - (b / a) * dl / (L + dl);
        Rw = aTN * asinhExpSlope(u) * dudw + kr * dl;
        return aTN * asinhExp(u) - A + kr * dl;
    };
    double hi = std::log(A / kr), lo = hi - 80.0;
    if (eval(lo) >= 0.0) {  // the contact cannot creep even 1e-35 of the trial's slip: stuck
        res.state.force_N = trial;
        res.state.alpha = alphaAged;
        res.tangent_N_per_m = epsT;
        return res;
    }
    // Start: the hint, else the creep rate at the trial force (F unchanged, α aged).
    double w = slipHint > 0.0 ? std::log(slipHint)
                              : std::log(std::sinh(std::min(A / aTN, 700.0))) - (mu + b * alphaAged) / a + logScale;
    if (!(w > lo && w < hi)) w = 0.5 * (lo + hi);
    const double ftol = 1e-13 * (A + tN);
    bool ok = false;
    int it = 0;
    double R = eval(w);
    for (; it < 200; ++it) {
        if (R > 0.0) hi = w; else lo = w;
        if (std::abs(R) <= ftol || hi - lo <= 1e-14) { ok = true; break; }
        double wn = Rw > 0.0 ? w - R / Rw : 0.5 * (lo + hi);
        if (!(wn > lo && wn < hi)) wn = 0.5 * (lo + hi);
        w = wn;
        R = eval(w);
    }
    const double dl = std::exp(w);
    res.iterations = it + 1;
    res.converged = ok;
    res.slipIncrement_m = dl;
    res.state.force_N = s * (A - kr * dl);
    res.state.alpha = alpha;
    res.tangent_N_per_m = Rw > 0.0 ? epsT * (1.0 - kr * dl / Rw) : 0.0;
    res.stuck = dl < kStickVelocity * dt;
    return res;
}

}  // namespace stickslip
