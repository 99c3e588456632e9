#include "simulate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <variant>

namespace stickslip {

namespace {

RunResult failedRun(std::string why) {
    RunResult r;
    r.status = RunStatus::Failed;
    r.message = std::move(why);
    return r;
}

// A measured slip history, each interval in the fewest sub-steps of at most dt.
RunResult simulateHistory(const SimParams& p, const FrictionLaw& law, const SlipHistory& history, const RunControl& ctl) {
    const double dtIn = (history.t_s.size() > 1) ? (history.t_s.back() - history.t_s.front()) /
                                                       static_cast<double>(history.t_s.size() - 1)
                                                 : p.integration.dt_s;
    const double subSteps = std::max(1.0, std::ceil(dtIn / p.integration.dt_s - 1e-9));
    const double intervals = history.t_s.empty() ? 0.0 : static_cast<double>(history.t_s.size() - 1);
    if (std::string why = stepBudgetProblem(subSteps * intervals, p.integration.maxSteps); !why.empty())
        return failedRun(why);
    const int sub = subSteps < 2147483647.0 ? static_cast<int>(subSteps) : 2147483647;
    return simulatePrescribed(law, p.rig.normalForce_N, history, sub, ctl);
}

// The harmonic slip of the drive, g = A sin(ωt + φ), imposed on the contact.
RunResult simulateHarmonicSlip(const SimParams& p, const FrictionLaw& law, const RunControl& ctl) {
    if (std::string why = stepBudgetProblem(harmonicRunSteps(p), p.integration.maxSteps); !why.empty())
        return failedRun(why);
    // Harmonic slip g = A sin(ωt + φ), evaluated exactly at every step (not interpolated
    // between output samples: decimating the output must not change the model).
    const long every = p.integration.outputEvery();
    const double dt = p.integration.dt_s;
    const double T = p.drive.period();
    const long drop = std::lround(p.transientCycles * T / dt);
    const long total = drop + std::lround(p.cycles * T / dt);
    const double A = p.drive.amplitude_m, w = p.drive.omega(), ph = p.drive.phase_rad, tN = p.rig.normalForce_N;
    RunResult r;
    r.samples.reserve(static_cast<size_t>(std::min<long>((total - drop) / every + 2, 1L << 20)));
    LawState st;
    double gPrev = A * std::sin(ph);
    double slipSinceOutput = 0.0;
    bool stuck = true;
    auto record = [&](long i) {
        const double t = static_cast<double>(i) * dt;
        Sample o;
        o.t_s = t;
        o.stage_m = A * std::sin(w * t + ph);
        o.relVel_mps = A * w * std::cos(w * t + ph);
        o.force_N = st.force_N;
        o.ratio = st.force_N / tN;
        o.alpha = st.alpha;
        o.slipRate_mps = slipSinceOutput / (static_cast<double>(every) * dt);
        o.stuck = stuck;
        ctl.output(r.samples, o);
    };
    if (drop == 0) record(0);
    std::visit(
        [&](const auto& l) {
            for (long i = 1; i <= total; ++i) {
                if ((i & 4095) == 0) {
                    if (ctl.cancelled()) { r.status = RunStatus::Cancelled; r.message = "cancelled"; return; }
                    if (ctl.progress) ctl.progress(static_cast<double>(i) / static_cast<double>(total));
                }
                const double g = A * std::sin(w * static_cast<double>(i) * dt + ph);
                const ReturnMapResult rm = l.returnMap(st, g - gPrev, dt, tN);
                ++r.stats.steps;
                r.stats.lawIterations += rm.iterations;
                if (!rm.converged || !std::isfinite(rm.state.force_N) || !std::isfinite(rm.state.alpha)) {
                    char buf[200];
                    std::snprintf(buf, sizeof buf, "step %ld at t = %.9g s: return mapping failed (F = %g, alpha = %g)",
                                  i, static_cast<double>(i) * dt, rm.state.force_N, rm.state.alpha);
                    r.status = RunStatus::Failed;
                    r.message = buf;
                    return;
                }
                st = rm.state;
                gPrev = g;
                stuck = rm.stuck;
                if (rm.stuck) ++r.stats.stuckSteps;
                slipSinceOutput += rm.slipIncrement_m;
                if (i >= drop && ((i - drop) % every) == 0) {
                    if (i == drop) slipSinceOutput = 0.0;
                    record(i);
                    slipSinceOutput = 0.0;
                }
            }
        },
        law);
    return r;
}

}  // namespace

RunResult simulate(const SimParams& p, const RunControl& ctl, const SlipHistory* history) {
    if (p.setup == SetupKind::Dynamics) return simulateDynamics(p, ctl);
    const ParamIssues issues = p.validate();
    if (!issues.empty()) return failedRun(formatIssues(issues));
    const FrictionLaw law = makeLaw(p);
    if (history) return simulateHistory(p, law, *history, ctl);
    return simulateHarmonicSlip(p, law, ctl);
}

}  // namespace stickslip
