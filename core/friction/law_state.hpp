// State and step result shared by every friction law.
#pragma once

#include <array>

namespace stickslip {

// State of the contact: the friction force and the internal state variable.
struct LawState {
    double force_N = 0.0;  // F (t_T in the paper): force of the stage on the slider [N]
    double alpha = 0.0;    // α, state variable of the rate-state law [-] (unused by Coulomb)
    // Extra internal variables for laws extended by effects (e.g. accumulated slip, time
    // stuck, lagged force); each extended law documents its use. Base laws leave them 0.
    std::array<double, 4> aux{};
};

// Result of one return mapping over a slip increment Δg in a time step Δt.
struct ReturnMapResult {
    LawState state;              // state at the end of the step
    double slipIncrement_m = 0;  // Δλ ≥ 0, irreversible (plastic) slip in the step [m]
    double tangent_N_per_m = 0;  // consistent tangent dF_{n+1}/dΔg
    bool stuck = true;           // Φ_trial ≤ 0: purely elastic step
    bool converged = true;       // the local solve met its tolerance
    int iterations = 0;          // local Newton/bisection iterations
};

}  // namespace stickslip
