#include "coulomb.hpp"

#include <cmath>

namespace stickslip {

std::vector<ParamDef> CoulombLaw::paramRows() { return {{.key = "mu"}, {.key = "epsT"}}; }

double* CoulombLaw::field(Params& p, std::string_view key) {
    if (key == "mu") return &p.mu;
    if (key == "epsT") return &p.epsT_N_per_m;
    return nullptr;
}

ParamIssues CoulombParams::validate() const {
    ParamIssues out;
    checkParam("mu", mu, out);
    checkParam("epsT", epsT_N_per_m, out);
    return out;
}

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
