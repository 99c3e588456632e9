// Elasto-viscoplastic, rate- and state-dependent friction (paper Eqs. 1–4):
//   Φ     = |F| − t_N (μ + K1(α)),   K1(α) = C1 (exp(α/r) − 1)        (1)
//   λ̇     = (1/η) ⟨Φ/t_N⟩                                             (3)
//   Ḟ     = ε_T (V − λ̇ sign F)                                        (4)
//   α̇     = −(λ̇/D_c)(α + C2 λ̇),  C2 = 1/v_c                          (2)
#pragma once

#include <limits>

#include <string_view>
#include <vector>

#include "../param_table.hpp"
#include "law_state.hpp"

namespace stickslip {

// Elasto-viscoplastic rate- and state-dependent law (Eqs. 1–4).
struct RateStateParams {
    double mu = 0.25;                 // μ, static coefficient of friction [-]
    double eta_s_per_m = 0.6;         // η, fluidity (viscosity) [s/m]
    double Dc_m = 20.0e-6;            // D_c, critical slip distance [m]
    double C1 = 0.25;                 // C1, amplitude of K1(α) [-]
    double r = 1.0;                   // r, scale of α in K1(α) = C1 (exp(α/r) − 1) [-]
    double vc_mps = 0.1;              // v_c = 1/C2, characteristic velocity [m/s]
    double epsT_N_per_m = 1.0e6;      // ε_T, tangential penalty stiffness [N/m]
    ParamIssues validate() const;
    double C2() const { return 1.0 / vc_mps; }  // [s/m]
};

struct RateStateLaw {
    using Params = RateStateParams;
    static constexpr const char* kKey = "rate-state";     // --model, run files, sessions
    static constexpr const char* kLabel = "rate-state";   // legends
    static constexpr bool kViscous = true;                // slip rate follows the overstress (Eq. 3)
    // While Φ ≤ 0 the force is F_n + ε_T Δg exactly and the state does not evolve (Eqs. 1–4):
    // the integrator may step the stuck rig in closed form (integrate/stuck_flow.hpp).
    static constexpr bool kElasticStick = true;
    // The law's rows of the parameter table (param_table.hpp), with `field` left empty: the
    // registry writes them through field().
    static std::vector<ParamDef> paramRows();
    static double* field(Params& p, std::string_view key);

    RateStateParams params;

    // Backward-Euler return mapping over one step (derivation in rate_state.cpp).
    ReturnMapResult returnMap(const LawState& s, double dg_m, double dt_s, double normalForce_N) const {
        return returnMapFromTrial(s, s.force_N + params.epsT_N_per_m * dg_m, params.epsT_N_per_m, dt_s, normalForce_N);
    }
    // The same return mapping from a given elastic trial force, with the force falling by
    // `returnStiffness` per unit slip: ε_T alone for the bare law, or ε_T K/(K + ε_T) when the
    // contact is in series with a structure of stiffness K (the condensed Newmark step).
    // tangent_N_per_m is dF/d(trial force) · ε_T.
    ReturnMapResult returnMapFromTrial(const LawState& s, double trialForce_N, double returnStiffness_N_per_m,
                                       double dt_s, double normalForce_N) const {
        return prepare(returnStiffness_N_per_m, dt_s, normalForce_N).returnMapFromTrial(s, trialForce_N);
    }

    // The return map with every constant of a step (k_r, Δt, t_N) computed once: the form
    // used inside time loops, where these do not change from step to step.
    // A Prepared is per-run scratch (one per time loop, never shared between threads): it
    // remembers exp(α/r) of the last state it produced, which a stuck step (α unchanged) reuses.
    struct Prepared {
        double epsT, kr, tN, muTN, C1, C1TN, invR, invDc, visc, c2q, krPlusVisc;
        double cachedAlpha = std::numeric_limits<double>::quiet_NaN(), cachedExp = 1.0;
        // slipHint_m: a guess of Δλ (e.g. the previous step's), used to start Newton when slipping.
        ReturnMapResult returnMapFromTrial(const LawState& s, double trialForce_N, double slipHint_m = 0.0);
    };
    Prepared prepare(double returnStiffness_N_per_m, double dt_s, double normalForce_N) const;

    double K1(double alpha) const;                                    // Eq. 1
    // α̇ = −(λ̇/D_c)(α + C2 λ̇) (Eq. 2) at slip rate λ̇ ≥ 0: the explicit part of the
    // second-order step (integrate/trbdf2.hpp).
    double alphaRate(double alpha, double slipRate_mps) const;
    double slipFunction(const LawState& s, double normalForce_N) const;  // Φ [N]
    // |F|/t_N in steady sliding at |V| (Eq. 5): μ + K1(−C2|V|) + η|V|.
    double steadyStateRatio(double slipVelocity_mps) const;
    // α in steady sliding at |V|: −C2 |V|.
    double steadyStateAlpha(double slipVelocity_mps) const;
    double epsT() const { return params.epsT_N_per_m; }
};

}  // namespace stickslip
