#include "section_stepping.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stickslip {

namespace {

StepReport stepReportOf(const AdaptiveReport& a) {
    StepReport r;
    r.status = a.status;
    r.message = a.message;
    r.stepsDone = a.accepted;
    r.newtonIterations = a.baseSteps;
    r.lawIterations = a.lawIterations;
    r.stuckSteps = a.stuckSteps;
    return r;
}

}  // namespace

SectionStepping SectionStepping::of(const SimParams& p, long requestedN) {
    SectionStepping st;
    st.stepsPerPeriod = stepsPerPeriodFor(p, requestedN);
    st.period_s = p.drive.period();
    st.adaptive = p.integration.tolerance > 0.0;
    if (st.adaptive) st.options.tolerance = p.integration.tolerance;
    st.options.maxSteps = p.integration.maxSteps;
    return st;
}

double SectionStepping::phaseTime(double phase_rad) const {
    if (!adaptive)  // the fixed-step clock: offset · dt with dt = T/N, rounded as the model's dt is
        return static_cast<double>(detail::phaseOffsetSteps(phase_rad, stepsPerPeriod)) *
               (period_s / static_cast<double>(stepsPerPeriod));
    return phase_rad / (2 * std::numbers::pi) * period_s;
}

StepReport SectionStepping::toPhase(const DynamicsModel& m, DynState& s, double phase_rad, const RunControl& ctl) const {
    if (!adaptive) return advanceQuiet(m, s, detail::phaseOffsetSteps(phase_rad, stepsPerPeriod), ctl);
    const double t = phaseTime(phase_rad);
    if (!(t > s.t)) return {};
    return stepReportOf(advanceAdaptive(m, s, t, options, {}, RunControl{ctl.cancel, {}, {}}));
}

StepReport SectionStepping::settle(const DynamicsModel& m, DynState& s, long cycles, const RunControl& ctl) const {
    if (!adaptive) return detail::settleCycles(m, s, stepsPerPeriod, cycles, ctl);
    if (cycles <= 0) return {};
    StepReport r = stepReportOf(
        advanceAdaptive(m, s, s.t + static_cast<double>(cycles) * period_s, options, {}, RunControl{ctl.cancel, {}, {}}));
    if (r.status == RunStatus::Ok && ctl.cancelled()) {
        r.status = RunStatus::Cancelled;
        r.message = "cancelled";
    }
    return r;
}

PoincareSection SectionStepping::section(const DynamicsModel& m, DynState& s, long settleCycles, long cycles,
                                         const RunControl& ctl) const {
    if (!adaptive) return poincareSectionFrom(m, s, stepsPerPeriod, settleCycles, cycles, ctl);
    return poincareSectionAdaptive(m, s, period_s, settleCycles, cycles, options, ctl);
}

PoincareSection poincareSectionAdaptive(const DynamicsModel& m, DynState& s, double period_s, long settle,
                                        long cycles, const AdaptiveOptions& o, const RunControl& ctl) {
    PoincareSection out;
    out.period_s = period_s;
    // One adaptive call over the settled and the sampled cycles: a second call at the end of the
    // settling would restart the step-size control there, and the short closing step plus the
    // restart perturb the orbit by about the tolerance — enough to keep the first sampled cycles
    // from matching the period test (seen at A = 2 mm in the Fig. 20 set).
    const double tStart = s.t, ts = tStart + static_cast<double>(settle) * period_s;
    const double tEnd = ts + static_cast<double>(cycles) * period_s;
    const double tiny = 1e-9 * period_s;  // sample times reached up to rounding
    long k = 1;                           // next sample: ts + kT
    double stuckTime = 0.0, vmax = 0.0;
    auto obs = [&](const DynState& a, const DynState& b) {
        if (b.t > ts) {
            const double from = std::max(a.t, ts);
            if (b.stuck) stuckTime += b.t - from;
            else ++out.slipSteps;
            vmax = std::max(vmax, std::abs(m.stage.velocity(b.t) - b.v));
        }
        for (double t; k <= cycles && (t = ts + static_cast<double>(k) * period_s) <= b.t + tiny; ++k)
            detail::appendSectionPoint(m, denseState(m, a, b, std::min(t, b.t)), out);
        if (ctl.progress && tEnd > tStart) ctl.progress(std::min(1.0, (b.t - tStart) / (tEnd - tStart)));
    };
    const AdaptiveReport rep = advanceAdaptive(m, s, tEnd, o, obs, RunControl{ctl.cancel, {}, {}});
    out.maxRelVel_mps = vmax;
    out.stickFraction = cycles > 0 ? std::clamp(stuckTime / (tEnd - ts), 0.0, 1.0) : 0.0;
    if (rep.status != RunStatus::Ok || ctl.cancelled()) {
        out.status = rep.status != RunStatus::Ok ? rep.status : RunStatus::Cancelled;
        out.message = rep.status != RunStatus::Ok ? rep.message : "cancelled";
    }
    return out;
}

}  // namespace stickslip
