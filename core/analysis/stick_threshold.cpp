#include "stick_threshold.hpp"

#include <cmath>
#include <complex>

namespace stickslip {

double stickThresholdAmplitude(const SimParams& p) {
    const bool coulomb = p.law == LawKind::Coulomb;
    const double mu = coulomb ? p.coulomb.mu : p.rateState.mu;
    const double eps = coulomb ? p.coulomb.epsT_N_per_m : p.rateState.epsT_N_per_m;
    const double w = p.drive.omega();
    const std::complex<double> dyn(p.rig.stiffness_N_per_m - p.rig.mass_kg * w * w, p.rig.damping_Ns_per_m * w);
    // Exact series compliance |1/Z + 1/ε_T|; equals 1/|Z| + 1/ε_T to O((cω/Z)²) when Z is near real positive.
    return mu * p.rig.normalForce_N * std::abs(1.0 / dyn + 1.0 / eps);
}

}  // namespace stickslip
