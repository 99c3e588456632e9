#include "prescribed.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <variant>

namespace stickslip {

SlipHistory SlipHistory::fromVelocity(std::vector<double> t, std::vector<double> v, double g0) {
    SlipHistory h;
    h.slip_m.resize(t.size());
    if (!t.empty()) h.slip_m[0] = g0;
    for (size_t i = 1; i < t.size() && i < v.size(); ++i)
        h.slip_m[i] = h.slip_m[i - 1] + 0.5 * (v[i] + v[i - 1]) * (t[i] - t[i - 1]);
    h.t_s = std::move(t);
    h.velocity_mps = std::move(v);
    return h;
}

SlipHistory SlipHistory::fromSlip(std::vector<double> t, std::vector<double> g) {
    SlipHistory h;
    h.t_s = std::move(t);
    h.slip_m = std::move(g);
    return h;
}

SlipHistory SlipHistory::harmonic(const DriveParams& d, double cycles, double dt) {
    SlipHistory h;
    const long n = std::lround(cycles * d.period() / dt);
    h.t_s.resize(static_cast<size_t>(n + 1));
    h.slip_m.resize(h.t_s.size());
    h.velocity_mps.resize(h.t_s.size());
    const double w = d.omega();
    for (long i = 0; i <= n; ++i) {
        const double t = static_cast<double>(i) * dt;
        h.t_s[static_cast<size_t>(i)] = t;
        h.slip_m[static_cast<size_t>(i)] = d.amplitude_m * std::sin(w * t + d.phase_rad);
        h.velocity_mps[static_cast<size_t>(i)] = d.amplitude_m * w * std::cos(w * t + d.phase_rad);
    }
    return h;
}

ParamIssues SlipHistory::validate() const {
    auto one = [](const char* field, std::string text) { return ParamIssues{ParamIssue::note(field, std::move(text))}; };
    if (t_s.size() < 2) return one("t", "slip history needs at least two samples");
    if (slip_m.size() != t_s.size()) return one("slip", "slip history: slip and time columns differ in length");
    if (!velocity_mps.empty() && velocity_mps.size() != t_s.size())
        return one("velocity", "slip history: velocity and time differ in length");
    if (!normalForce_N.empty() && normalForce_N.size() != t_s.size())
        return one("tN", "slip history: normal force and time differ in length");
    for (size_t i = 0; i < t_s.size(); ++i) {
        char buf[160];
        if (!std::isfinite(t_s[i]) || !std::isfinite(slip_m[i])) {
            std::snprintf(buf, sizeof buf, "slip history: non-finite value at sample %zu", i);
            return one("slip", buf);
        }
        if (i > 0 && !(t_s[i] > t_s[i - 1])) {
            std::snprintf(buf, sizeof buf, "slip history: time does not increase at sample %zu (t = %g s)", i, t_s[i]);
            return one("t", buf);
        }
        if (!normalForce_N.empty() && !(normalForce_N[i] > 0.0)) {
            std::snprintf(buf, sizeof buf, "slip history: normal force must be > 0, is %g at sample %zu", normalForce_N[i], i);
            return one("tN", buf);
        }
    }
    return {};
}

namespace {

template <class Law>
RunResult runPrescribed(const Law& law, double tNconst, const SlipHistory& h, int substeps, const RunControl& ctl,
                        LawState st) {
    RunResult res;
    const size_t n = h.t_s.size();
    res.samples.reserve(std::min<size_t>(n, size_t{1} << 20));
    auto record = [&](size_t i, double slipRate, bool stuck) {
        Sample s;
        const double tN = h.normalForce_N.empty() ? tNconst : h.normalForce_N[i];
        s.t_s = h.t_s[i];
        s.stage_m = h.slip_m[i];
        s.slider_m = 0.0;
        s.sliderVel_mps = 0.0;
        if (!h.velocity_mps.empty()) s.relVel_mps = h.velocity_mps[i];
        else if (i > 0) s.relVel_mps = (h.slip_m[i] - h.slip_m[i - 1]) / (h.t_s[i] - h.t_s[i - 1]);
        s.force_N = st.force_N;
        s.ratio = st.force_N / tN;
        s.alpha = st.alpha;
        s.slipRate_mps = slipRate;
        s.stuck = stuck;
        ctl.output(res.samples, s);
    };
    record(0, 0.0, true);
    // The law's per-step constants are prepared once and kept while Δt and t_N stay the same
    // (every step of a uniformly sampled history with constant t_N): the same numbers as
    // law.returnMap(st, Δg, Δt, t_N) step by step, without recomputing them (and exp(α/r) of
    // a stuck step) every step.
    auto prep = law.prepare(law.epsT(), 1.0, tNconst);
    double prepDt = std::numeric_limits<double>::quiet_NaN(), prepTN = prepDt;
    for (size_t i = 1; i < n; ++i) {
        if ((i & 1023) == 0) {
            if (ctl.cancelled()) { res.status = RunStatus::Cancelled; res.message = "cancelled"; return res; }
            if (ctl.progress) ctl.progress(static_cast<double>(i) / static_cast<double>(n));
        }
        const double dt = (h.t_s[i] - h.t_s[i - 1]) / substeps;
        const double dg = (h.slip_m[i] - h.slip_m[i - 1]) / substeps;
        const double tN0 = h.normalForce_N.empty() ? tNconst : h.normalForce_N[i - 1];
        const double tN1 = h.normalForce_N.empty() ? tNconst : h.normalForce_N[i];
        double slip = 0.0;
        bool stuck = true;
        for (int j = 1; j <= substeps; ++j) {
            const double tN = tN0 + (tN1 - tN0) * j / substeps;
            if (!(dt == prepDt && tN == prepTN)) {
                prep = law.prepare(law.epsT(), dt, tN);
                prepDt = dt;
                prepTN = tN;
            }
            const ReturnMapResult r = prep.returnMapFromTrial(st, st.force_N + law.epsT() * dg);  // = law.returnMap(st, dg, dt, tN)
            res.stats.lawIterations += r.iterations;
            ++res.stats.steps;
            if (!r.converged || !std::isfinite(r.state.force_N) || !std::isfinite(r.state.alpha)) {
                char buf[200];
                std::snprintf(buf, sizeof buf, "step %ld at t = %.9g s: return mapping failed (F = %g, alpha = %g)",
                              res.stats.steps, h.t_s[i - 1] + j * dt, r.state.force_N, r.state.alpha);
                res.status = RunStatus::Failed;
                res.message = buf;
                return res;
            }
            st = r.state;
            slip += r.slipIncrement_m;
            stuck = r.stuck;
            if (r.stuck) ++res.stats.stuckSteps;
        }
        record(i, slip / (h.t_s[i] - h.t_s[i - 1]), stuck);
    }
    return res;
}

}  // namespace

RunResult simulatePrescribed(const FrictionLaw& law, double tN, const SlipHistory& h, int substeps,
                             const RunControl& ctl, LawState initial) {
    const std::string bad = formatIssues(h.validate());
    if (!bad.empty() || !(tN > 0.0) || substeps < 1) {
        RunResult r;
        r.status = RunStatus::Failed;
        r.message = !bad.empty() ? bad : (!(tN > 0.0) ? "tN = " + std::to_string(tN) + " is out of range: must be > 0"
                                                        : "substeps must be >= 1");
        return r;
    }
    return std::visit([&](const auto& l) { return runPrescribed(l, tN, h, substeps, ctl, initial); }, law);
}

}  // namespace stickslip
