// Ideal elasto-plastic Coulomb friction (paper's comparison model): Φ = |F| − μ t_N.
#pragma once

#include "../params.hpp"
#include "law_state.hpp"

namespace stickslip {

struct CoulombLaw {
    CoulombParams params;

    // Return mapping in closed form: elastic trial F_tr = F_n + ε_T Δg; if |F_tr| > μ t_N the
    // force is projected back to the slip surface, Δλ = (|F_tr| − μ t_N)/ε_T, tangent 0.
    ReturnMapResult returnMap(const LawState& s, double dg_m, double dt_s, double normalForce_N) const {
        return returnMapFromTrial(s, s.force_N + params.epsT_N_per_m * dg_m, params.epsT_N_per_m, dt_s, normalForce_N);
    }
    // From a given trial force, the force falling by `returnStiffness` per unit slip (see RateStateLaw).
    ReturnMapResult returnMapFromTrial(const LawState& s, double trialForce_N, double returnStiffness_N_per_m,
                                       double dt_s, double normalForce_N) const {
        return prepare(returnStiffness_N_per_m, dt_s, normalForce_N).returnMapFromTrial(s, trialForce_N);
    }
    // The return map with the step's constants fixed (see RateStateLaw::Prepared).
    struct Prepared {
        double epsT, kr, muTN;
        ReturnMapResult returnMapFromTrial(const LawState& s, double trialForce_N, double /*slipHint_m*/ = 0.0) const;
    };
    Prepared prepare(double returnStiffness_N_per_m, double /*dt_s*/, double normalForce_N) const {
        return {params.epsT_N_per_m, returnStiffness_N_per_m, params.mu * normalForce_N};
    }

    // Φ for a given state [N] (Eq. 1 with K1 ≡ 0).
    double slipFunction(const LawState& s, double normalForce_N) const;
    // |F|/t_N in steady sliding: μ, independent of the velocity.
    double steadyStateRatio(double slipVelocity_mps) const;
    double epsT() const { return params.epsT_N_per_m; }
};

}  // namespace stickslip
