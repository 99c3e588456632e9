// Elasto-viscoplastic, rate- and state-dependent friction (paper Eqs. 1–4):
//   Φ     = |F| − t_N (μ + K1(α)),   K1(α) = C1 (exp(α/r) − 1)        (1)
//   λ̇     = (1/η) ⟨Φ/t_N⟩                                             (3)
//   Ḟ     = ε_T (V − λ̇ sign F)                                        (4)
//   α̇     = −(λ̇/D_c)(α + C2 λ̇),  C2 = 1/v_c                          (2)
#pragma once

#include "../params.hpp"
#include "law_state.hpp"

namespace stickslip {

struct RateStateLaw {
    RateStateParams params;

    // Backward-Euler return mapping over one step (derivation in rate_state.cpp).
    ReturnMapResult returnMap(const LawState& s, double dg_m, double dt_s, double normalForce_N) const;

    double K1(double alpha) const;                                    // Eq. 1
    double slipFunction(const LawState& s, double normalForce_N) const;  // Φ [N]
    // |F|/t_N in steady sliding at |V| (Eq. 5): μ + K1(−C2|V|) + η|V|.
    double steadyStateRatio(double slipVelocity_mps) const;
    // α in steady sliding at |V|: −C2 |V|.
    double steadyStateAlpha(double slipVelocity_mps) const;
    double epsT() const { return params.epsT_N_per_m; }
};

}  // namespace stickslip
