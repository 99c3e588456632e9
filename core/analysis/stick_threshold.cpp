#include "stick_threshold.hpp"

#include <cmath>

#include "../friction/friction_law.hpp"
#include <complex>

namespace stickslip {

double stickThresholdAmplitude(const SimParams& p) {
    const double mu = lawMu(p), eps = lawEpsT(p);
    const double w = p.drive.omega();
    const std::complex<double> dyn(p.rig.stiffness_N_per_m - p.rig.mass_kg * w * w, p.rig.damping_Ns_per_m * w);
    // Exact series compliance |1/Z + 1/ε_T|; equals 1/|Z| + 1/ε_T to O((cω/Z)²) when Z is near real positive.
    return mu * p.rig.normalForce_N * std::abs(1.0 / dyn + 1.0 / eps);
}

}  // namespace stickslip
