// direction_asymmetry: μ differs with the slip direction.
#pragma once

#include "effect.hpp"

namespace stickslip::identify {

// μ is used for positive slip (F > 0); μ − d for negative slip.
struct DirectionAsymmetry {
    double mu_pos_minus_mu_neg = 0.0;  // d = μ₊ − μ₋ [-]

    double muShift(double trialForce_N) const { return trialForce_N < 0.0 ? -mu_pos_minus_mu_neg : 0.0; }

    static EffectInfo info() {
        return {"direction_asymmetry",
                "The contact is stronger in one slip direction than the other (machining lay, "
                "tilted asperities, a slightly inclined surface or a pre-load that adds to one "
                "direction), so the friction plateau is higher for positive slip than for negative "
                "slip. The paper's law is odd in V.",
                "Residual of one sign during positive slip and the other during negative slip: a "
                "strong correlation with sign(V), weak with |V|.",
                {{"mu_pos_minus_mu_neg", "-", 0.0, -0.3, 0.3, false, 0.0, true}},
                {"signV"},
                {true, true}};
    }
};

}  // namespace stickslip::identify
