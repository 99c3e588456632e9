#include "rate_state.hpp"

#include <algorithm>
#include <cmath>

#include "slip_first_root.hpp"
#include "slip_newton.hpp"

namespace stickslip {

// Fit ranges: in the prescribed set-up t_N is a reference load (e.g. a band tension), so μ,
// C1 and η are "per unit reference load" and may be far above 1.
std::vector<ParamDef> RateStateLaw::paramRows() {
    using G = ParamGroup;
    return {
        {.key = "mu", .label = "μ", .quantity = "dimensionless", .doc = "Static coefficient of friction, Eq. 1",
         .group = G::FrictionLaw, .lower = 0, .fit = {0.01, 2.0, false}, .fitPrescribed = {1e-3, 1e3, true},
         .sliderMin = 0.0, .sliderMax = 1.0, .decimals = 4},
        {.key = "eta", .label = "η", .unit = "s/m", .quantity = "a fluidity", .doc = "Fluidity (viscosity), Eq. 3",
         .group = G::FrictionLaw, .lower = 0, .lowerOpen = true, .fit = {1e-4, 50.0, true}, .fitPrescribed = {1e-4, 1e4, true},
         .displayUnit = "s/m", .sliderMin = 0.01, .sliderMax = 10.0, .logSlider = true, .decimals = 4},
        {.key = "Dc", .label = "D_c", .unit = "m", .quantity = "a length", .doc = "Critical slip distance, Eq. 2",
         .group = G::FrictionLaw, .lower = 0, .lowerOpen = true, .fit = {1e-8, 1e-2, true}, .displayUnit = "µm",
         .displayScale = 1e6, .sliderMin = 0.5, .sliderMax = 1000.0, .logSlider = true, .decimals = 2},
        {.key = "C1", .label = "C1", .quantity = "dimensionless", .doc = "Amplitude of K1(α), Eq. 1",
         .group = G::FrictionLaw, .lower = 0, .fit = {0.0, 2.0, false}, .fitPrescribed = {1e-4, 1e3, true},
         .sliderMin = 0.0, .sliderMax = 1.0, .decimals = 4},
        {.key = "r", .label = "r", .quantity = "dimensionless", .doc = "Scale of α in K1(α), Eq. 1",
         .group = G::FrictionLaw, .lower = 0, .lowerOpen = true, .fit = {0.05, 20.0, true}, .sliderMin = 0.05,
         .sliderMax = 10.0, .decimals = 3},
        {.key = "vc", .label = "v_c", .unit = "m/s", .quantity = "a velocity", .doc = "Characteristic velocity 1/C2, Eq. 2",
         .group = G::FrictionLaw, .lower = 0, .lowerOpen = true, .fit = {1e-4, 10.0, true}, .displayUnit = "m/s",
         .sliderMin = 0.001, .sliderMax = 1.0, .logSlider = true, .decimals = 4},
        {.key = "epsT", .label = "ε_T", .unit = "N/m", .quantity = "a stiffness", .doc = "Tangential penalty stiffness, Eq. 4",
         .group = G::FrictionLaw, .lower = 0, .lowerOpen = true, .fit = {1e2, 1e10, true}, .displayUnit = "N/m",
         .sliderMin = 1.0e3, .sliderMax = 1.0e8, .logSlider = true, .decimals = 0},
    };
}

double* RateStateLaw::field(Params& p, std::string_view key) {
    if (key == "mu") return &p.mu;
    if (key == "eta") return &p.eta_s_per_m;
    if (key == "Dc") return &p.Dc_m;
    if (key == "C1") return &p.C1;
    if (key == "r") return &p.r;
    if (key == "vc") return &p.vc_mps;
    if (key == "epsT") return &p.epsT_N_per_m;
    return nullptr;
}

ParamIssues RateStateParams::validate() const {
    ParamIssues out;
    for (const char* k : {"mu", "eta", "Dc", "C1", "r", "vc", "epsT"})
        checkParam(k, *RateStateLaw::field(const_cast<RateStateParams&>(*this), k), out);
    return out;
}

double RateStateLaw::K1(double alpha) const { return params.C1 * (std::exp(alpha / params.r) - 1.0); }

double RateStateLaw::slipFunction(const LawState& s, double tN) const {
    return std::abs(s.force_N) - tN * (params.mu + K1(s.alpha));
}

double RateStateLaw::alphaRate(double alpha, double v) const {
    return -v / params.Dc_m * (alpha + params.C2() * v);
}

double RateStateLaw::steadyStateAlpha(double v) const { return -params.C2() * std::abs(v); }

double RateStateLaw::steadyStateRatio(double v) const {
    return params.mu + K1(steadyStateAlpha(v)) + params.eta_s_per_m * std::abs(v);
}

// Return mapping (backward Euler on λ and α, as in computational plasticity).
// (ε below is the return stiffness k_r: ε_T for the bare law; ε_T K/(K+ε_T) in series.)
//
// Elastic predictor:  F_tr = F_n + ε_T Δg,  a = |F_tr|,  s = sign F_tr,
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
// Consistent tangent: R depends on Δg only through a (∂R/∂a = 1, ∂a/∂Δg = s ε_T), hence
//   dΔλ/dΔg = −s ε_T / R',  dF/dΔg = s (s ε_T − ε dΔλ/dΔg) = ε_T (1 + ε/R'),
// with R' = dR/dΔλ = −ε − η t_N/Δt − t_N K1'(α) dα/dΔλ.
RateStateLaw::Prepared RateStateLaw::prepare(double kr, double dt, double tN) const {
    const RateStateParams& p = params;
    Prepared q;
    q.epsT = p.epsT_N_per_m;
    q.kr = kr;
    q.tN = tN;
    q.muTN = p.mu * tN;
    q.C1 = p.C1;
    q.C1TN = p.C1 * tN;
    q.invR = 1.0 / p.r;
    q.invDc = 1.0 / p.Dc_m;
    q.visc = p.eta_s_per_m * tN / dt;      // η t_N / Δt  [N/m]
    q.c2q = q.invDc / (p.vc_mps * dt);     // C2 / (D_c Δt) [1/m²]
    q.krPlusVisc = kr + q.visc;
    return q;
}

ReturnMapResult RateStateLaw::Prepared::returnMapFromTrial(const LawState& st, double trial, double slipHint) {
    ReturnMapResult res;
    const double eps = kr;
    const double a = std::abs(trial);
    const double e0 = (st.alpha == cachedAlpha) ? cachedExp : std::exp(st.alpha * invR);  // exp(α_n / r)
    cachedAlpha = st.alpha;
    cachedExp = e0;
    const double K1n = C1 * (e0 - 1.0);
    const double phiTrial = a - muTN - tN * K1n;      // Φ_trial, Eq. 1
    res.state = st;
    if (phiTrial <= 0.0) {
        res.state.force_N = trial;
        res.tangent_N_per_m = epsT;
        res.stuck = true;
        return res;
    }
    res.stuck = false;
    const double s = trial >= 0.0 ? 1.0 : -1.0;

    // Residual R and R' at Δλ = x; also α(x) and exp(α(x)/r).
    double e = e0;
    auto eval = [&](double x, double& R, double& dR, double& alpha) {
        const double invDen = 1.0 / (1.0 + x * invDc);
        alpha = (st.alpha - c2q * x * x) * invDen;
        const double dalpha = (-2.0 * c2q * x - alpha * invDc) * invDen;
        e = std::exp(alpha * invR);
        R = a - eps * x - muTN - C1TN * (e - 1.0) - visc * x;
        dR = -krPlusVisc - C1TN * invR * e * dalpha;
    };

    double hi = (phiTrial + tN * (K1n + C1)) / krPlusVisc;
    double R = phiTrial, alpha = st.alpha;
    // R'(0) from the exponential already at hand: dα/dΔλ(0) = −α_n / D_c.
    double dR = -krPlusVisc + C1TN * invR * e0 * st.alpha * invDc;
    // Keep the force from changing sign (possible only when C1 > μ at extreme rates).
    if (hi * eps > a) {
        // R(a/ε) < 0 is usually certain from α(a/ε) alone, without the exponential
        // (slip_newton.hpp); otherwise evaluate it.
        const double xA = a / eps;
        const double uA = (st.alpha - c2q * xA * xA) / (1.0 + xA * invDc) * invR;
        if (!slipResidualCertainlyNegative(a, krPlusVisc * xA, muTN, C1TN, uA)) {
            double Ra = 0, dRa = 0, alphaA = 0;
            eval(xA, Ra, dRa, alphaA);
            if (Ra > 0.0) {
                res.state.force_N = 0.0;
                res.state.alpha = alphaA;
                cachedAlpha = alphaA;
                cachedExp = e;
                res.slipIncrement_m = xA;
                res.tangent_N_per_m = 0.0;
                return res;
            }
        }
        hi = a / eps;
    }

    // Safeguarded Newton from Δλ = 0 (R(0) = Φ_trial > 0, so 0 is the lower bracket). R may
    // have three roots; the step takes the first (slip_first_root.hpp).
    const SlipShape shape{false, st.alpha, c2q / invDc, invDc, invR, C1TN * invR, krPlusVisc};
    auto evalR = [&](double xx, double& Rx, double& dRx) { eval(xx, Rx, dRx, alpha); };
    const SlipRoot root = solveSlipFirstRoot(evalR, shape, e0, R, dR, hi, slipHint, 1e-13 * (a + tN));
    const double x = root.x;
    dR = root.dR;
    res.iterations = root.iterations;
    res.converged = root.converged;
    res.slipIncrement_m = x;
    res.state.force_N = s * (a - eps * x);
    res.state.alpha = alpha;
    cachedAlpha = alpha;
    cachedExp = e;
    res.tangent_N_per_m = (dR < 0.0) ? epsT * (1.0 + eps / dR) : 0.0;
    return res;
}

}  // namespace stickslip
