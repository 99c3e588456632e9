// frictional_lag: first-order memory of the friction strength.
#pragma once

#include <cmath>

#include "effect.hpp"

namespace stickslip::identify {

// The strength Y = t_N (μ + K1(α)) the contact can carry does not follow the law at once
// but through a first-order lag of time constant τ:  dY_act/dt = (Y_law − Y_act)/τ.
struct FrictionalLag {
    double tau_s = 1e-3;  // τ, lag time constant [s]

    // Weights of the exact update over a step Δt with Y_law linear in time between its values at
    // the step's ends (first-order hold):  Y_act(Δt) = E Y_act + (q − E) Y_law,0 + w Y_law,1,
    // E = e^{−Δt/τ}, q = (τ/Δt)(1 − E), w = 1 − q.  τ → 0 gives Y_law,1, the law without lag
    // (its strength implicit in α, as the return map has it); τ → ∞ freezes Y_act.
    struct Hold {
        double E, q, w;
    };
    Hold hold(double dt_s) const {
        const double x = dt_s / tau_s;
        const double em1 = std::expm1(-x);  // E − 1, exact for small x
        const double q = x > 0.0 ? -em1 / x : 1.0;
        return {1.0 + em1, q, 1.0 - q};
    }
    double lagged(double yActual_N, double yLaw0_N, double yLaw1_N, double dt_s) const {
        const Hold h = hold(dt_s);
        return h.E * yActual_N + (h.q - h.E) * yLaw0_N + h.w * yLaw1_N;
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
                {{"tau_s", "s", 2e-3, 1e-6, 0.2, true}},
                {"dVdt", "time_since_reversal"},
                {true, true}};
    }
};

}  // namespace stickslip::identify
