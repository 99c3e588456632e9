#include "coulomb.hpp"

#include <cmath>

namespace stickslip {

double CoulombLaw::slipFunction(const LawState& s, double tN) const { return std::abs(s.force_N) - params.mu * tN; }

double CoulombLaw::steadyStateRatio(double) const { return params.mu; }

ReturnMapResult CoulombLaw::Prepared::returnMapFromTrial(const LawState& s, double trial, double) const {
    ReturnMapResult r;
    const double phiTrial = std::abs(trial) - muTN;
    r.state = s;
    if (phiTrial <= 0.0) {
        r.state.force_N = trial;
        r.tangent_N_per_m = epsT;
        r.stuck = true;
        return r;
    }
    r.state.force_N = trial > 0.0 ? muTN : -muTN;
    r.slipIncrement_m = phiTrial / kr;
    r.tangent_N_per_m = 0.0;
    r.stuck = false;
    return r;
}

}  // namespace stickslip
