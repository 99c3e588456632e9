// frictional_lag: first-order memory of the friction strength.
#pragma once

#include <cmath>

#include "effect.hpp"

namespace stickslip::identify {

// The strength Y = t_N (μ + K1(α)) the contact can carry does not follow the law at once
// but through a first-order lag of time constant τ:  dY_act/dt = (Y_law − Y_act)/τ.
struct FrictionalLag {
    double tau_s = 1e-3;  // τ, lag time constant [s]

    // Exact update of the lagged strength over a step Δt with Y_law held at its start value.
    double lagged(double yActual_N, double yLaw_N, double dt_s) const {
        return yLaw_N + (yActual_N - yLaw_N) * std::exp(-dt_s / tau_s);
    }

    static EffectInfo info() {
        return {"frictional_lag",
                "The friction force has a first-order memory: the strength the contact can carry "
                "follows the rate-and-state value only through a lag of time constant tau (real "
                "asperity junctions need time to grow and shear). After a velocity change the force "
                "keeps its old level for about tau; rising and falling velocity then give different "
                "forces and the F/t_N-velocity loop can turn counter-clockwise, which the paper's law "
                "(clockwise loops only) cannot produce.",
                "Residual correlated with dV/dt (acceleration of the slip) and concentrated just after "
                "reversals and at the start of slip; loops of the residual against V are open.",
                {{"tau_s", "s", 2e-3, 1e-4, 0.2, true}},
                {"dVdt", "time_since_reversal"},
                {true, true}};
    }
};

}  // namespace stickslip::identify
