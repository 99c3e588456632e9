#include "poincare.hpp"

#include "section_stepping.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stickslip {

ParamIssues PoincareOptions::validate() const {
    ParamIssues out;
    if (stepsPerPeriod < 0) out.push_back({"stepsPerPeriod", double(stepsPerPeriod), ">= 0 (0 = from dt)"});
    if (!(phase_rad >= 0 && phase_rad < 2 * std::numbers::pi)) out.push_back({"phase", phase_rad, "in [0, 2π)"});
    if (settleCycles < 0) out.push_back({"settle", double(settleCycles), ">= 0"});
    if (cycles < 1) out.push_back({"cycles", double(cycles), ">= 1"});
    return out;
}

long stepsPerPeriodFor(const SimParams& p, long requested) {
    if (requested > 0) return requested;
    const double n = std::round(p.drive.period() / p.integration.dt_s);
    return std::max(1L, static_cast<long>(n));
}

DynamicsModel poincareModel(const SimParams& p, long stepsPerPeriod) {
    DynamicsModel m = DynamicsModel::fromParams(p);
    m.dt_s = p.drive.period() / static_cast<double>(std::max(1L, stepsPerPeriod));
    return m;
}

namespace detail {

long phaseOffsetSteps(double phase_rad, long n) {
    long k = std::lround(phase_rad / (2 * std::numbers::pi) * static_cast<double>(n));
    k %= n;
    if (k < 0) k += n;
    return k;
}

void appendSectionPoint(const DynamicsModel& m, const DynState& s, PoincareSection& out) {
    out.t_s.push_back(s.t);
    out.slider_m.push_back(s.x);
    out.relVel_mps.push_back(m.stage.velocity(s.t) - s.v);
    out.ratio.push_back(s.law.force_N / m.rig.normalForce_N);
    out.alpha.push_back(s.law.alpha);
}

StepReport advanceSampledCycle(const DynamicsModel& m, DynState& s, long n, PoincareSection& out, long& stuckSteps,
                               const RunControl& ctl) {
    double vmax = out.maxRelVel_mps;
    // Stage velocity by the rotation recurrence (a cosine per step cost ~15 % of a sampled cycle).
    StageSequence stage(m.stage, s.t, m.dt_s);
    auto obs = [&](const DynState& st) {
        stage.next();
        const double V = std::abs(stage.velocity() - st.v);
        if (V > vmax) vmax = V;
    };
    StepReport rep = advance(m, s, n, obs, ctl);
    out.maxRelVel_mps = vmax;
    stuckSteps += rep.stuckSteps;
    out.slipSteps += rep.stepsDone - rep.stuckSteps;
    if (rep.status == RunStatus::Ok) appendSectionPoint(m, s, out);
    return rep;
}

StepReport settleCycles(const DynamicsModel& m, DynState& s, long n, long cycles, const RunControl& ctl) {
    StepReport total;
    for (long c = 0; c < cycles; ++c) {
        StepReport rep = advanceQuiet(m, s, n, ctl);
        total.stepsDone += rep.stepsDone;
        if (rep.status != RunStatus::Ok) {
            rep.stepsDone = total.stepsDone;
            return rep;
        }
        if (ctl.cancelled()) {
            total.status = RunStatus::Cancelled;
            total.message = "cancelled";
            return total;
        }
    }
    return total;
}

}  // namespace detail

static void finishSection(PoincareSection& out, long stuckSteps) {
    const long total = stuckSteps + out.slipSteps;
    out.stickFraction = total > 0 ? static_cast<double>(stuckSteps) / static_cast<double>(total) : 0.0;
}

PoincareSection poincareSectionFrom(const DynamicsModel& m, DynState& s, long stepsPerPeriod, long settle,
                                    long cycles, const RunControl& ctl) {
    PoincareSection out;
    out.period_s = m.dt_s * static_cast<double>(stepsPerPeriod);
    RunControl quiet{ctl.cancel, {}, {}};
    const double total = static_cast<double>(settle + cycles);
    for (long c = 0; c < settle; ++c) {
        StepReport rep = advanceQuiet(m, s, stepsPerPeriod, quiet);
        if (rep.status != RunStatus::Ok || ctl.cancelled()) {
            out.status = rep.status != RunStatus::Ok ? rep.status : RunStatus::Cancelled;
            out.message = rep.status != RunStatus::Ok ? rep.message : "cancelled";
            return out;
        }
        if (ctl.progress) ctl.progress(static_cast<double>(c + 1) / total);
    }
    out.t_s.reserve(cycles);
    out.slider_m.reserve(cycles);
    out.relVel_mps.reserve(cycles);
    out.ratio.reserve(cycles);
    out.alpha.reserve(cycles);
    long stuck = 0;
    for (long c = 0; c < cycles; ++c) {
        StepReport rep = detail::advanceSampledCycle(m, s, stepsPerPeriod, out, stuck, quiet);
        if (rep.status != RunStatus::Ok || ctl.cancelled()) {
            out.status = rep.status != RunStatus::Ok ? rep.status : RunStatus::Cancelled;
            out.message = rep.status != RunStatus::Ok ? rep.message : "cancelled";
            break;
        }
        if (ctl.progress) ctl.progress(static_cast<double>(settle + c + 1) / total);
    }
    finishSection(out, stuck);
    return out;
}

PoincareSection sectionOfRun(const RunResult& run, double period_s) {
    PoincareSection out;
    out.period_s = period_s;
    if (run.period.stepsPerPeriod <= 0) {
        out.status = RunStatus::Failed;
        out.message = "the run recorded no once-per-period states (prescribed set-up, or dt does not divide the "
                      "forcing period)";
        return out;
    }
    const size_t n = run.period.samples.size();
    out.t_s.reserve(n);
    out.slider_m.reserve(n);
    out.relVel_mps.reserve(n);
    out.ratio.reserve(n);
    out.alpha.reserve(n);
    for (const Sample& s : run.period.samples) {
        out.t_s.push_back(s.t_s);
        out.slider_m.push_back(s.slider_m);
        out.relVel_mps.push_back(s.relVel_mps);
        out.ratio.push_back(s.ratio);
        out.alpha.push_back(s.alpha);
    }
    out.maxRelVel_mps = run.period.maxRelVel_mps;
    out.slipSteps = run.stats.steps - run.stats.stuckSteps;
    finishSection(out, run.stats.stuckSteps);
    out.status = run.status;
    out.message = run.message;
    return out;
}

PoincareSection poincareSection(const SimParams& p, const PoincareOptions& opt, const RunControl& ctl) {
    ParamIssues issues = p.validate();
    ParamIssues more = opt.validate();
    issues.insert(issues.end(), more.begin(), more.end());
    if (!issues.empty()) {
        PoincareSection out;
        out.status = RunStatus::Failed;
        out.message = formatIssues(issues);
        return out;
    }
    const SectionStepping st = SectionStepping::of(p, opt.stepsPerPeriod);
    const DynamicsModel m = poincareModel(p, st.stepsPerPeriod);
    DynState s = m.initialState(0.0);
    if (opt.phase_rad > 0) {
        StepReport rep = st.toPhase(m, s, opt.phase_rad, ctl);
        if (rep.status != RunStatus::Ok) {
            PoincareSection out;
            out.period_s = p.drive.period();
            out.status = rep.status;
            out.message = rep.message;
            return out;
        }
    }
    return st.section(m, s, opt.settleCycles, opt.cycles, ctl);
}

}  // namespace stickslip
