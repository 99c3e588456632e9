#include "coulomb.hpp"

#include <cmath>

namespace stickslip {

double CoulombLaw::slipFunction(const LawState& s, double tN) const { return std::abs(s.force_N) - params.mu * tN; }

double CoulombLaw::steadyStateRatio(double) const { return params.mu; }

ReturnMapResult CoulombLaw::returnMap(const LawState& s, double dg, double /*dt*/, double tN) const {
    ReturnMapResult r;
    const double eps = params.epsT_N_per_m;
    const double trial = s.force_N + eps * dg;
    const double phiTrial = std::abs(trial) - params.mu * tN;
    r.state.alpha = s.alpha;
    if (phiTrial <= 0.0) {
        r.state.force_N = trial;
        r.tangent_N_per_m = eps;
        r.stuck = true;
        return r;
    }
    const double sign = trial > 0.0 ? 1.0 : -1.0;
    r.state.force_N = sign * params.mu * tN;
    r.slipIncrement_m = phiTrial / eps;
    r.tangent_N_per_m = 0.0;
    r.stuck = false;
    r.iterations = 0;
    return r;
}

}  // namespace stickslip
