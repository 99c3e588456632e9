// stick_healing: static friction grows with the time spent stuck.
#pragma once

#include <cmath>

#include "effect.hpp"

namespace stickslip::identify {

// An extra strength h (in units of μ) grows while the contact sticks,
//   dh/dt = (Δμ_s − h)/τ_h     (stuck),
// and is erased by slip over a distance D_h:  dh/dλ = −h/D_h.
struct StickHealing {
    double dmu_static = 0.0;   // Δμ_s, largest extra static coefficient [-]
    double tau_heal_s = 0.05;  // τ_h, healing time constant [s]
    double Dh_m = 1e-4;        // D_h, slip distance that erases the healed strength [m]

    double healWhileStuck(double h, double dt_s) const {
        return dmu_static + (h - dmu_static) * std::exp(-dt_s / tau_heal_s);
    }
    double eraseBySlip(double h, double slip_m) const { return h * std::exp(-slip_m / Dh_m); }

    static EffectInfo info() {
        return {"stick_healing",
                "While the contact sticks, asperity junctions creep and bond, so the static friction "
                "grows with the time spent stuck (Dieterich-Rabinowicz ageing) and breaks away at a "
                "higher force after a long stick than after a short one. The paper's law has no "
                "healing: its state variable does not evolve while stuck.",
                "Residual peaks at the onset of slip whose size grows with the preceding time stuck: "
                "correlation with 'time stuck before slip', near zero in steady sliding.",
                {{"dmu_static", "-", 0.02, 0.0, 0.5, false, 0.0, true},
                 {"tau_heal_s", "s", 0.05, 1e-3, 5.0, true},
                 {"Dh_m", "m", 1e-4, 1e-6, 1e-2, true}},
                {"time_stuck_before_slip"},
                {true, true}};
    }
};

}  // namespace stickslip::identify
