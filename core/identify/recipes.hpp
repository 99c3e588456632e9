// The paper's own parameter recipes (section 4.2, Fig. 14), usable on any run:
//  - μ from the peak of F/t_N in a constant-velocity pull (Fig. 14a–b): while the pull
//    velocity is constant, the ratio first rises elastically and peaks when slip starts
//    (static value, α = 0 so K1 = 0), then settles to the kinetic plateau (Eq. 5).
//  - η from an impulse (Eq. 7, Fig. 14c–d): a jump Δv of the slip velocity leaves the state
//    α unchanged (Eq. 6), so the ratio jumps by Δs = η Δv: η = Δs / Δv.
#pragma once

#include <string>
#include <vector>

namespace stickslip::identify {

struct PullEstimate {
    bool ok = false;
    std::string message;
    double mu = 0.0;              // peak |F|/t_N during the pull [-]
    double kineticRatio = 0.0;    // median |F|/t_N over the second half of the pull [-]
    double pullVelocity_mps = 0;  // median |V| during the pull [m/s]
    size_t begin = 0, end = 0;    // the pull: samples [begin, end)
    size_t peakIndex = 0;
};

// V: slip velocity, F: friction force, t_N: normal load. The pull is the longest stretch where
// |V| stays within `velocityTolerance` (relative) of its plateau value and keeps its sign.
PullEstimate muFromPull(const std::vector<double>& velocity_mps, const std::vector<double>& force_N, double normalForce_N,
                        double velocityTolerance = 0.2);

struct ImpulseEstimate {
    bool ok = false;
    std::string message;
    double eta_s_per_m = 0.0;  // Δs/Δv
    double dv_mps = 0.0;       // velocity jump Δ|V|
    double ds = 0.0;           // ratio jump Δ(|F|/t_N)
    size_t index = 0;          // sample before the jump
};

// The impulse is the largest change of |V| between consecutive samples; Δ is taken between
// `before` samples before it and `after` samples after it (short, so that α has not moved:
// the slip in that time must stay well below D_c).
ImpulseEstimate etaFromImpulse(const std::vector<double>& velocity_mps, const std::vector<double>& force_N,
                               double normalForce_N, size_t before = 1, size_t after = 1);

}  // namespace stickslip::identify
