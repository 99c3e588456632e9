#include "simulate.hpp"

#include <algorithm>
#include <cmath>

namespace stickslip {

RunResult simulate(const SimParams& p, const RunControl& ctl, const SlipHistory* history) {
    if (p.setup == SetupKind::Dynamics) return simulateDynamics(p, ctl);
    const ParamIssues issues = p.validate();
    if (!issues.empty()) {
        RunResult r;
        r.status = RunStatus::Failed;
        r.message = formatIssues(issues);
        return r;
    }
    const FrictionLaw law = makeLaw(p);
    if (history) {
        const double dtIn = (history->t_s.size() > 1) ? (history->t_s.back() - history->t_s.front()) /
                                                            static_cast<double>(history->t_s.size() - 1)
                                                      : p.integration.dt_s;
        const int sub = std::max(1, static_cast<int>(std::ceil(dtIn / p.integration.dt_s - 1e-9)));
        return simulatePrescribed(law, p.rig.normalForce_N, *history, sub, ctl);
    }
    const long every = p.integration.outputEvery();
    const double dtOut = every * p.integration.dt_s;
    SlipHistory h = SlipHistory::harmonic(p.drive, p.transientCycles + p.cycles, dtOut);
    RunResult r = simulatePrescribed(law, p.rig.normalForce_N, h, static_cast<int>(every), ctl);
    const long drop = std::lround(p.transientCycles * p.drive.period() / dtOut);
    if (drop > 0 && static_cast<size_t>(drop) < r.samples.size())
        r.samples.erase(r.samples.begin(), r.samples.begin() + drop);
    return r;
}

}  // namespace stickslip
