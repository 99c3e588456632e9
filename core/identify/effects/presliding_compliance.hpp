// presliding_compliance: finite tangential stiffness of the contact before gross slip.
#pragma once

#include <limits>

#include "effect.hpp"

namespace stickslip::identify {

// A tangential compliance 1/k_t in series with the law's penalty stiffness ε_T: the contact
// deflects elastically by F/k_t before gross slip, ε_eff = ε_T k_t/(ε_T + k_t).
struct PreslidingCompliance {
    double kt_N_per_m = 1e5;  // k_t, tangential contact stiffness [N/m]

    double effectiveStiffness(double epsT_N_per_m) const {
        return epsT_N_per_m * kt_N_per_m / (epsT_N_per_m + kt_N_per_m);
    }

    static EffectInfo info() {
        return {"presliding_compliance",
                "Before gross slip the contact deflects elastically (asperity and bulk shear, "
                "Mindlin micro-slip): the force builds up over a finite pre-sliding displacement "
                "F/k_t instead of almost at once. The baseline treats the contact as nearly rigid "
                "(epsT large).",
                "Residual after each reversal and at the start of stick while the force is rising: "
                "the model's force rises faster than measured; correlation with time since "
                "reversal and with the displacement.",
                {{"kt_N_per_m", "N/m", 2e5, 1e2, 1e8, true, std::numeric_limits<double>::infinity()}},
                {"time_since_reversal", "displacement"},
                {true, true}};
    }
};

}  // namespace stickslip::identify
