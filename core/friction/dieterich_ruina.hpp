// Dieterich–Ruina rate-and-state friction with the aging law, in the regularised form used
// in rock and earthquake mechanics (Rice & Ben-Zion 1996; Lapusta et al. 2000):
//   |F|/t_N = a asinh( V/(2 V0) exp(Ψ/a) ),   Ψ = μ0 + b ln(V0 θ / L)
//   θ̇ = 1 − V θ / L                                           (aging, Dieterich 1979)
// set in the paper's elasto-viscoplastic frame: F = ε_T (g − λ), V = λ̇. The stored state is
// α = ln(V0 θ / L) (0 at steady sliding at V0), so Ψ = μ0 + b α.
// Steady state at |V|: α = ln(V0/|V|), |F|/t_N = a asinh(|V|/(2V0) exp((μ0 + b ln(V0/|V|))/a))
// ≈ μ0 + (a − b) ln(|V|/V0): velocity weakening for b > a.
// The slip rate is never exactly zero (creep): a step counts as stuck when λ̇ < kStickVelocity.
#pragma once

#include <string_view>
#include <vector>

#include "../param_table.hpp"
#include "law_state.hpp"

namespace stickslip {

struct DieterichRuinaParams {
    double mu = 0.25;             // μ0, friction coefficient at steady sliding at V0 [-]
    double a = 0.01;              // a, direct-effect coefficient [-]
    double b = 0.015;             // b, evolution-effect coefficient [-]
    double Dc_m = 20.0e-6;        // L, critical slip distance of the aging law [m]
    double V0_mps = 1.0e-3;       // V0, reference velocity [m/s]
    double epsT_N_per_m = 1.0e6;  // ε_T, tangential penalty stiffness [N/m]
    ParamIssues validate() const;
};

struct DieterichRuinaLaw {
    using Params = DieterichRuinaParams;
    static constexpr const char* kKey = "dieterich-ruina";
    static constexpr const char* kLabel = "Dieterich–Ruina";
    static constexpr bool kViscous = true;
    static constexpr double kStickVelocity = 1e-6;  // [m/s]: slower creep counts as stuck
    static std::vector<ParamDef> paramRows();
    static double* field(Params& p, std::string_view key);

    DieterichRuinaParams params;

    ReturnMapResult returnMap(const LawState& s, double dg_m, double dt_s, double normalForce_N) const {
        return prepare(params.epsT_N_per_m, dt_s, normalForce_N).returnMapFromTrial(s, s.force_N + params.epsT_N_per_m * dg_m);
    }
    ReturnMapResult returnMapFromTrial(const LawState& s, double trialForce_N, double returnStiffness_N_per_m,
                                       double dt_s, double normalForce_N) const {
        return prepare(returnStiffness_N_per_m, dt_s, normalForce_N).returnMapFromTrial(s, trialForce_N);
    }
    // Backward Euler on λ and θ, solved for ln Δλ (derivation in dieterich_ruina.cpp).
    struct Prepared {
        double epsT, kr, dt, tN, mu, a, b, L, V0;
        ReturnMapResult returnMapFromTrial(const LawState& s, double trialForce_N, double slipHint_m = 0.0) const;
    };
    Prepared prepare(double returnStiffness_N_per_m, double dt_s, double normalForce_N) const {
        const Params& p = params;
        return {p.epsT_N_per_m, returnStiffness_N_per_m, dt_s, normalForce_N, p.mu, p.a, p.b, p.Dc_m, p.V0_mps};
    }

    // |F|/t_N at slip velocity |V| and state α (the law's strength).
    double strengthRatio(double slipVelocity_mps, double alpha) const;
    // Φ = |F| − t_N · strength at the slip rate kStickVelocity: > 0 once the contact slides visibly.
    double slipFunction(const LawState& s, double normalForce_N) const;
    double steadyStateRatio(double slipVelocity_mps) const;
    double steadyStateAlpha(double slipVelocity_mps) const;
    double epsT() const { return params.epsT_N_per_m; }
};

}  // namespace stickslip
