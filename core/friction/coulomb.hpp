// Ideal elasto-plastic Coulomb friction (paper's comparison model): Φ = |F| − μ t_N.
#pragma once

#include <string_view>
#include <vector>

#include "../param_table.hpp"
#include "law_state.hpp"

namespace stickslip {

// Ideal elasto-plastic Coulomb law: Φ = |F| − μ t_N.
struct CoulombParams {
    double mu = 0.25;                 // μ [-]
    double epsT_N_per_m = 1.0e6;      // ε_T [N/m]
    ParamIssues validate() const;
};

struct CoulombLaw {
    using Params = CoulombParams;
    static constexpr const char* kKey = "coulomb";
    static constexpr const char* kLabel = "Coulomb";
    static constexpr bool kViscous = false;
    // While Φ ≤ 0 the force is F_n + ε_T Δg exactly and the state does not evolve (Eqs. 1–4):
    // the integrator may step the stuck rig in closed form (integrate/stuck_flow.hpp).
    static constexpr bool kElasticStick = true;
    static std::vector<ParamDef> paramRows();  // μ and ε_T: shared with the rate-state law
    static double* field(Params& p, std::string_view key);

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
