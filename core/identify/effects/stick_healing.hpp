// stick_healing: static friction grows with the time spent stuck (Dieterich ageing).
#pragma once

#include <algorithm>
#include <cmath>

#include "effect.hpp"
#include "../../friction/slip_newton.hpp"

namespace stickslip::identify {

// Dieterich's ageing law (Dieterich 1979; Ruina 1983; Marone 1998, Eq. 7): the contact has an
// age θ that grows one to one with time and is renewed by slip over a distance D_h,
//   dθ/dt = 1 − θ λ̇ / D_h,
// and adds the strength  h = b ln(1 + θ/t_c)  (in units of μ) to the law's. Stuck, θ grows with
// the time stuck and the breakaway force with its logarithm; in steady sliding θ = D_h/V, so the
// same state also weakens the friction with velocity (b ln(1 + D_h/(V t_c))). θ starts at 0
// (a fresh contact); it forgets that start within D_h of slip. b = 0 is the model without it.
struct StickHealing {
    double b_heal = 0.0;    // b, healing rate per e-fold of contact age [-]
    double tc_s = 0.01;     // t_c, age below which the contact has not healed yet [s]
    double Dh_m = 2e-5;     // D_h, slip distance that renews the contact [m]

    double strength(double age_s) const { return b_heal * std::log1p(std::max(age_s, 0.0) / tc_s); }
    double ageWhileStuck(double age_s, double dt_s) const { return age_s + dt_s; }
    // Exact over a step of slip `slip_m` at constant rate in `dt_s`:
    // θ e^{−s/D} + Δt (D/s)(1 − e^{−s/D}), which tends to θ + Δt as s → 0.
    double ageAfterSlip(double age_s, double slip_m, double dt_s) const {
        const double x = std::abs(slip_m) / Dh_m;
        const double renewed = x > 1e-12 ? -std::expm1(-x) / x : 1.0;
        return age_s * expOrZero(-x) + dt_s * renewed;
    }

    static EffectInfo info() {
        return {"stick_healing",
                "While the contact sticks, asperity junctions creep and bond, so the static friction "
                "grows with the logarithm of the time spent stuck (Dieterich ageing: contact age "
                "theta, strength b ln(1 + theta/t_c), theta renewed over a slip distance D_h) and "
                "breaks away at a higher force after a long stick than after a short one; in steady "
                "sliding the same age D_h/V makes the friction fall with velocity. The paper's law has "
                "no healing: its state variable does not evolve while stuck.",
                "Residual peaks at the onset of slip whose size grows with the preceding time stuck: "
                "correlation with 'time stuck before slip', and a velocity-weakening part the base "
                "law's C1 and v_c take up.",
                {{"b_heal", "-", 0.01, 0.0, 0.2, false, 0.0, true},
                 {"tc_s", "s", 0.01, 1e-5, 10.0, true},
                 {"Dh_m", "m", 2e-5, 1e-7, 1e-2, true}},
                {"time_stuck_before_slip"},
                {true, true},
                // b alone trades off with t_c (b ln(1 + θ/t_c) at the sticks the runs contain is
                // what they show): the size is the strength after the runs' typical stick
                // (OperatingPoint: the duration-weighted median).
                {"strength_after_median_stick",
                 [](const std::map<std::string, double>& p, const OperatingPoint& op) {
                     const StickHealing h{paramOr(p, "b_heal"), paramOr(p, "tc_s"), paramOr(p, "Dh_m")};
                     return h.strength(op.stickDuration_s);
                 }}};
    }
};

}  // namespace stickslip::identify
