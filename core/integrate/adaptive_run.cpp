// The public side of the adaptive integrator (adaptive.hpp) that does not step: its options'
// checks, the dense output between accepted steps, and a full run sampled on the output grid.
// The stepping itself is in adaptive.cpp.
#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>
#include <vector>

#include "adaptive.hpp"

namespace stickslip {

ParamIssues AdaptiveOptions::validate() const {
    ParamIssues out;
    // Below 1e-5 the steps at grazing stops (F at the slip bound with V ≈ 0) reach the round-off
    // floor of the Newmark update and the run chatters or goes wrong (measured at 1e-6 and 1e-7
    // on the Fig. 20 set): refused until that is fixed (docs/adaptive.md, open points).
    if (!(std::isfinite(tolerance) && tolerance >= 1e-5 && tolerance <= 0.5))
        out.push_back({"tolerance", tolerance, ">= 1e-5 and <= 0.5"});
    if (!(std::isfinite(maxStep_s) && maxStep_s >= 0.0)) out.push_back({"max_step", maxStep_s, ">= 0 (0 = T/32)"});
    if (!(std::isfinite(minStep_s) && minStep_s >= 0.0)) out.push_back({"min_step", minStep_s, ">= 0 (0 = automatic)"});
    if (minStep_s > 0.0 && maxStep_s > 0.0 && minStep_s > maxStep_s)
        out.push_back({"min_step", minStep_s, "<= max_step"});
    if (!(std::isfinite(displacementScale_m) && displacementScale_m >= 0.0))
        out.push_back({"displacement_scale", displacementScale_m, ">= 0 (0 = automatic)"});
    if (maxSteps < 1) out.push_back({"max_steps", static_cast<double>(maxSteps), ">= 1"});
    return out;
}

DynState denseState(const DynamicsModel& m, const DynState& a, const DynState& b, double t) {
    const double h = b.t - a.t;
    if (!(h > 0.0) || t >= b.t) return b;
    if (t <= a.t) return a;
    const double th = (t - a.t) / h, th2 = th * th, th3 = th2 * th;
    const double h00 = 2 * th3 - 3 * th2 + 1, h10 = th3 - 2 * th2 + th, h01 = -2 * th3 + 3 * th2, h11 = th3 - th2;
    DynState s = b;
    s.t = t;
    s.x = h00 * a.x + h10 * h * a.v + h01 * b.x + h11 * h * b.v;
    s.v = h00 * a.v + h10 * h * a.a + h01 * b.v + h11 * h * b.a;
    s.u = m.stage.displacement(t);
    s.law.alpha = a.law.alpha + th * (b.law.alpha - a.law.alpha);
    // Stuck throughout a step of a law elastic in stick, F = F_a + ε_T (Δu − Δx) exactly (Eq. 4
    // with λ̇ = 0) and ẍ is Eq. 8's: both follow the x interpolant, as they must over the long
    // closed-form stuck steps (stuck_flow.hpp), which span ringing a line would cut across.
    const double eps = std::visit([](const auto& law) {
        if constexpr (requires { std::decay_t<decltype(law)>::kElasticStick; }) return law.epsT();
        else return 0.0;
    }, m.law);
    if (a.stuck && b.stuck && eps > 0.0) {
        s.law.force_N = a.law.force_N + eps * ((s.u - a.u) - (s.x - a.x));
        s.a = (s.law.force_N - m.rig.damping_Ns_per_m * s.v - m.rig.stiffness_N_per_m * s.x) / m.rig.mass_kg;
        return s;
    }
    // a from the derivative of the x interpolant would lose an order; interpolate linearly.
    s.a = a.a + th * (b.a - a.a);
    s.law.force_N = a.law.force_N + th * (b.law.force_N - a.law.force_N);
    return s;
}

RunResult simulateAdaptive(const SimParams& p, const AdaptiveOptions& o, const RunControl& ctl) {
    RunResult res;
    ParamIssues issues = p.validate();
    const ParamIssues more = o.validate();
    issues.insert(issues.end(), more.begin(), more.end());
    if (!issues.empty()) {
        res.status = RunStatus::Failed;
        res.message = formatIssues(issues);
        return res;
    }
    const DynamicsModel m = DynamicsModel::fromParams(p);
    DynState s = m.initialState(0.0);
    const double T = p.drive.period();
    const double t0 = p.transientCycles * T, tEnd = t0 + p.cycles * T;
    const double dtOut = p.integration.outputInterval_s;
    const long nOut = std::lround(p.cycles * T / dtOut);
    if (t0 > 0.0) {
        RunControl quiet;
        quiet.cancel = ctl.cancel;
        const AdaptiveReport rep = advanceAdaptive(m, s, t0, o, {}, quiet);
        if (rep.status != RunStatus::Ok) {
            res.status = rep.status;
            res.message = rep.message;
            return res;
        }
    }
    res.samples.reserve(static_cast<size_t>(std::min<long>(nOut + 2, 1L << 20)));
    ctl.output(res.samples, toSample(m, s));
    const long perPeriod = stepsPerPeriodDividing(p);
    res.period.stepsPerPeriod = perPeriod > 0 ? perPeriod : 1;
    long j = 1;                                                         // next output sample
    long kPer = static_cast<long>(std::floor(t0 / T + 1e-9)) + 1;      // next whole period kT > t0
    double maxV = 0.0;
    const double tiny = 1e-9 * dtOut;
    auto obs = [&](const DynState& a, const DynState& b) {
        maxV = std::max(maxV, std::abs(m.stage.velocity(b.t) - b.v));
        for (double t; j <= nOut && (t = t0 + static_cast<double>(j) * dtOut) <= b.t + tiny; ++j)
            ctl.output(res.samples, toSample(m, denseState(m, a, b, std::min(t, b.t))));
        for (double t; (t = static_cast<double>(kPer) * T) <= b.t + tiny && t <= tEnd + tiny; ++kPer)
            res.period.samples.push_back(toSample(m, denseState(m, a, b, std::min(t, b.t))));
        if (ctl.progress && (b.t - t0) > 0) ctl.progress(std::min(1.0, (b.t - t0) / (tEnd - t0)));
    };
    const AdaptiveReport rep = advanceAdaptive(m, s, tEnd, o, obs, ctl);
    res.stats.steps = rep.accepted;
    res.stats.newtonIterations = rep.baseSteps;
    res.stats.lawIterations = rep.lawIterations;
    res.stats.stuckSteps = rep.stuckSteps;
    res.period.maxRelVel_mps = maxV;
    res.status = rep.status;
    res.message = rep.message;
    return res;
}

}  // namespace stickslip
