#include "dynamics.hpp"

#include <algorithm>
#include <cmath>

#include "adaptive.hpp"

namespace stickslip {

const char* toString(RunStatus s) {
    switch (s) {
        case RunStatus::Ok: return "ok";
        case RunStatus::Cancelled: return "cancelled";
        case RunStatus::Failed: return "failed";
    }
    return "?";
}

DynamicsModel DynamicsModel::fromParams(const SimParams& p) {
    DynamicsModel m;
    m.rig = p.rig;
    m.stage = StageMotion::harmonic(p.drive);
    m.law = makeLaw(p);
    m.dt_s = p.integration.dt_s;
    return m;
}

DynState DynamicsModel::initialState(double t) const {
    DynState s;
    s.t = t;
    s.u = stage.displacement(t);
    return s;
}

Sample toSample(const DynamicsModel& m, const DynState& s) {
    Sample o;
    o.t_s = s.t;
    o.stage_m = s.u;
    o.slider_m = s.x;
    o.sliderVel_mps = s.v;
    o.relVel_mps = m.stage.velocity(s.t) - s.v;
    o.force_N = s.law.force_N;
    o.ratio = s.law.force_N / m.rig.normalForce_N;
    o.alpha = s.law.alpha;
    o.slipRate_mps = s.slipRate;
    o.stuck = s.stuck;
    return o;
}

ParamIssues DynamicsModel::validate() const {
    ParamIssues out = rig.validate();
    const ParamIssues lawIssues = std::visit([](const auto& l) { return l.params.validate(); }, law);
    out.insert(out.end(), lawIssues.begin(), lawIssues.end());
    if (!(std::isfinite(dt_s) && dt_s > 0.0)) out.push_back({"dt", dt_s, "> 0"});
    return out;
}

RunResult simulateDynamics(const DynamicsModel& m, DynState& s, long steps, long outputEvery, bool recordStart,
                           const RunControl& ctl, const PeriodRecording& period) {
    RunResult res;
    if (const ParamIssues issues = m.validate(); !issues.empty()) {
        res.status = RunStatus::Failed;
        res.message = formatIssues(issues);
        return res;
    }
    if (outputEvery < 1) outputEvery = 1;
    // Reserve what is cheap; long runs grow as they go (a cancelled run may never need it all).
    res.samples.reserve(static_cast<size_t>(std::min<long>(steps / outputEvery + 2, 1L << 20)));
    if (recordStart) ctl.output(res.samples, toSample(m, s));
    const long N = std::max(0L, period.stepsPerPeriod);
    res.period.stepsPerPeriod = N;
    // Countdowns to the next output sample and the next whole period (no division per step).
    long untilOutput = outputEvery;
    long untilPeriod = N > 0 ? N - ((period.stepsBefore % N) + N) % N : 0;
    if (N > 0) res.period.samples.reserve(static_cast<size_t>(std::min<long>(steps / N + 1, 1L << 16)));
    double maxV = 0.0;
    long done = 0;
    const long chunk = std::max<long>(outputEvery, 1L << 14) / outputEvery * outputEvery;
    while (done < steps) {
        const long n = std::min(chunk, steps - done);
        StepReport rep;
        if (N > 0) {
            // The stage velocity as advance() computes it (same recurrence from the same start).
            detail::StageSequence stage(m.stage, s.t, m.dt_s);
            auto obs = [&](const DynState& st) {
                stage.next();
                const double V = std::abs(stage.velocity() - st.v);
                if (V > maxV) maxV = V;
                if (--untilOutput == 0) {
                    ctl.output(res.samples, toSample(m, st));
                    untilOutput = outputEvery;
                }
                if (--untilPeriod == 0) {
                    res.period.samples.push_back(toSample(m, st));
                    untilPeriod = N;
                }
            };
            rep = advance(m, s, n, obs, ctl, done);
        } else {
            auto obs = [&](const DynState& st) {
                if (--untilOutput == 0) {
                    ctl.output(res.samples, toSample(m, st));
                    untilOutput = outputEvery;
                }
            };
            rep = advance(m, s, n, obs, ctl, done);
        }
        done += rep.stepsDone;
        res.stats.steps += rep.stepsDone;
        res.stats.newtonIterations += rep.newtonIterations;
        res.stats.lawIterations += rep.lawIterations;
        res.stats.stuckSteps += rep.stuckSteps;
        res.period.maxRelVel_mps = maxV;
        if (rep.status != RunStatus::Ok) {
            res.status = rep.status;
            res.message = rep.message;
            return res;
        }
        if (ctl.cancelled()) {
            res.status = RunStatus::Cancelled;
            res.message = "cancelled";
            return res;
        }
        if (ctl.progress) ctl.progress(static_cast<double>(done) / static_cast<double>(steps));
    }
    return res;
}

long stepsPerPeriodDividing(const SimParams& p) {
    const double T = p.drive.period(), dt = p.integration.dt_s;
    if (!(T > 0) || !(dt > 0) || !std::isfinite(T / dt) || T / dt > 1e12) return 0;
    const long N = std::lround(T / dt);
    return N >= 1 && std::abs(static_cast<double>(N) * dt - T) <= 1e-9 * T ? N : 0;
}

RunResult simulateDynamics(const SimParams& p, const RunControl& ctl) {
    const ParamIssues issues = p.validate();
    if (!issues.empty()) {
        RunResult r;
        r.status = RunStatus::Failed;
        r.message = formatIssues(issues);
        return r;
    }
    if (p.integration.tolerance > 0.0) {
        // Error-controlled steps (issue 15); the output grid is outputInterval_s exactly.
        AdaptiveOptions o;
        o.tolerance = p.integration.tolerance;
        o.maxSteps = p.integration.maxSteps;
        return simulateAdaptive(p, o, ctl);
    }
    if (std::string why = stepBudgetProblem(harmonicRunSteps(p), p.integration.maxSteps); !why.empty()) {
        RunResult r;
        r.status = RunStatus::Failed;
        r.message = why;
        return r;
    }
    const DynamicsModel m = DynamicsModel::fromParams(p);
    DynState s = m.initialState(0.0);
    const double T = p.drive.period();
    const long transientSteps = std::lround(p.transientCycles * T / p.integration.dt_s);
    const long recSteps = std::lround(p.cycles * T / p.integration.dt_s);
    if (transientSteps > 0) {
        RunControl quiet;
        quiet.cancel = ctl.cancel;
        StepReport rep = advanceQuiet(m, s, transientSteps, quiet);
        if (rep.status != RunStatus::Ok) {
            RunResult r;
            r.status = rep.status;
            r.message = rep.message;
            return r;
        }
    }
    return simulateDynamics(m, s, recSteps, p.integration.outputEvery(), true, ctl,
                            PeriodRecording{stepsPerPeriodDividing(p), transientSteps});
}

}  // namespace stickslip
