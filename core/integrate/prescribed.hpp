// Block driven with a prescribed slip history (paper Fig. 15a): the friction law alone
// predicts F(t)/t_N from the relative slip g(t) (or velocity V(t)); no slider dynamics.
#pragma once

#include <string>
#include <vector>

#include "../friction/friction_law.hpp"
#include "run_result.hpp"

namespace stickslip {

// Time samples of the relative slip g(t) = u − x, with optional per-sample velocity and
// normal force. Between samples g is interpolated linearly.
struct SlipHistory {
    std::vector<double> t_s;
    std::vector<double> slip_m;          // g
    std::vector<double> velocity_mps;    // V (optional; else backward difference of g)
    std::vector<double> normalForce_N;   // t_N per sample (optional; else constant)

    // From V(t), integrating by the trapezoid rule from g(t_0) = g0.
    static SlipHistory fromVelocity(std::vector<double> t, std::vector<double> v, double g0 = 0.0);
    // From g(t).
    static SlipHistory fromSlip(std::vector<double> t, std::vector<double> g);
    // g = A sin(ω t + φ) sampled every dt_s over `cycles` periods (stage moving, slider held).
    static SlipHistory harmonic(const DriveParams& d, double cycles, double dt_s);

    // Empty if usable, else what is wrong (sizes, time not increasing, non-finite): the first
    // problem of each kind, naming the sample.
    ParamIssues validate() const;
};

// Runs the law over the history with `substeps` equal steps per sample interval and
// returns one Sample per input sample (stage_m = g, slider_m = 0, relVel = V).
// normalForce_N is used where the history has no t_N column.
RunResult simulatePrescribed(const FrictionLaw& law, double normalForce_N, const SlipHistory& h, int substeps,
                             const RunControl& ctl = {}, LawState initial = {});

}  // namespace stickslip
