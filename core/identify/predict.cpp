#include "predict.hpp"

#include <algorithm>
#include <cmath>

#include "../integrate/dynamics.hpp"
#include "../integrate/prescribed.hpp"

namespace stickslip::identify {

using io::Signal;

std::vector<std::string> PredictSettings::validate() const {
    std::vector<std::string> v;
    if (stride < 1) v.push_back("stride = " + std::to_string(stride) + " must be >= 1");
    if (substeps < 1) v.push_back("substeps = " + std::to_string(substeps) + " must be >= 1");
    if (warmup_s < 0) v.push_back("warmup must be >= 0 s");
    if (!(dt_s > 0)) v.push_back("dt must be > 0 s");
    if (!(segment_s > 0)) v.push_back("segment length must be > 0 s");
    if (!(segmentSpacing_s >= segment_s)) v.push_back("segment spacing must be >= segment length");
    if (residualStride < 1) v.push_back("residual stride must be >= 1");
    if (!(slipStartFraction >= 0.0 && slipStartFraction < 1.0))
        v.push_back("slip start fraction = " + std::to_string(slipStartFraction) + " must be in [0, 1)");
    return v;
}

bool runParams(const CleanRun& run, const ModelSpec& spec, SimParams& p, std::string* error) {
    p = SimParams{};
    p.law = spec.law;
    double v = 0;
    for (const char* key : {"k", "m", "tN", "A", "f", "phase"})
        if (run.run.setting(key, v)) setParam(p, key, v);
    double zeta = -1;
    const bool haveC = run.run.setting("c", v);
    if (haveC) setParam(p, "c", v);
    for (const auto& [name, value] : spec.values) {
        if (name == "zeta") { zeta = value; continue; }
        if (!setParam(p, name, value, error)) return false;
    }
    if (zeta >= 0 && !haveC) p.rig.damping_Ns_per_m = dampingFromRatio(zeta, p.rig.stiffness_N_per_m, p.rig.mass_kg);
    if (spec.tieC1ToMu && !spec.values.count("C1")) p.rateState.C1 = p.rateState.mu;
    return true;
}

Prediction predictPrescribed(const CleanRun& run, const FrictionLaw& law, double tN, const PredictSettings& s) {
    Prediction pr;
    const io::Run& r = run.run;
    if (!r.has(Signal::Slip) || !r.has(Signal::Friction)) {
        pr.message = r.file + ": the prescribed set-up needs slip (or stage displacement) and friction force";
        return pr;
    }
    const size_t stride = static_cast<size_t>(s.stride);
    const size_t warm = static_cast<size_t>(std::lround(s.warmup_s / run.dt_s));
    const size_t first = run.begin > warm ? run.begin - warm : 0;
    SlipHistory h;
    std::vector<size_t> idx;
    for (size_t i = first; i < run.end; i += stride) idx.push_back(i);
    for (size_t i : idx) {
        h.t_s.push_back(r[Signal::Time][i]);
        h.slip_m.push_back(r[Signal::Slip][i]);
        if (r.has(Signal::RelVel)) h.velocity_mps.push_back(r[Signal::RelVel][i]);
        if (r.has(Signal::Normal)) h.normalForce_N.push_back(r[Signal::Normal][i]);
    }
    LawState init;
    init.force_N = r[Signal::Friction][first];
    const RunResult res = simulatePrescribed(law, tN, h, s.substeps, {}, init);
    if (!res.ok()) {
        pr.message = r.file + ": " + res.message;
        return pr;
    }
    std::vector<double> Fk(idx.size());
    for (size_t k = 0; k < idx.size(); ++k) Fk[k] = res.samples[k].force_N;
    if (s.filterPrediction && !run.filter.empty() && idx.size() > 1) {
        // Prediction at every measured sample (linear between law step boundaries), minus
        // the cleaned force, through the cleaning filter; back at the step boundaries.
        const std::vector<double>& F = r[Signal::Friction];
        const std::vector<double>& Fu = run.unfilteredForce_N.size() == F.size() ? run.unfilteredForce_N : F;
        const size_t last = idx.back();
        std::vector<double> d(last - first + 1);
        for (size_t k = 0; k + 1 < idx.size(); ++k)
            for (size_t i = idx[k]; i < idx[k + 1]; ++i) {
                const double a = static_cast<double>(i - idx[k]) / static_cast<double>(idx[k + 1] - idx[k]);
                d[i - first] = Fk[k] + a * (Fk[k + 1] - Fk[k]) - Fu[i];
            }
        d[last - first] = Fk.back() - Fu[last];
        d = filtfiltZeroExtended(run.filter, d);
        for (size_t k = 0; k < idx.size(); ++k) Fk[k] = F[idx[k]] + d[idx[k] - first];
    }
    for (size_t k = 0; k < idx.size(); ++k)
        if (idx[k] >= run.begin) {
            pr.index.push_back(idx[k]);
            pr.force_N.push_back(Fk[k]);
        }
    pr.ok = true;
    return pr;
}

namespace {

// The stage displacement over samples [s0, s0 + len] on the integration step grid (`sub`
// steps per sample), by cubic Hermite interpolation with central-difference slopes
// (Catmull–Rom) of the sampled u. Linear interpolation between 1 kHz samples would make
// u̇ jump at every sample (by ü·Δt, ≈ 1 mm/s on D05); through the contact stiffness ε_T those
// kicks drive the stick mode, and the fit retunes m* and ε_T to them (m* +4 standard errors
// on D05 with every other input exact).
StageMotion smoothStage(const std::vector<double>& t, const std::vector<double>& u, size_t s0, size_t len, long sub) {
    const size_t n = u.size();
    std::vector<double> ts, us;
    ts.reserve(len * static_cast<size_t>(sub) + 1);
    us.reserve(len * static_cast<size_t>(sub) + 1);
    for (size_t i = s0; i < s0 + len && i + 1 < n; ++i) {
        const double p0 = u[i > 0 ? i - 1 : i], p1 = u[i], p2 = u[i + 1], p3 = u[i + 2 < n ? i + 2 : i + 1];
        for (long q = 0; q < sub; ++q) {
            const double w = static_cast<double>(q) / static_cast<double>(sub);
            ts.push_back(t[i] + w * (t[i + 1] - t[i]));
            us.push_back(p1 + 0.5 * w * ((p2 - p0) + w * ((2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) + w * (3.0 * (p1 - p2) + p3 - p0))));
        }
    }
    const size_t e = std::min(s0 + len, n - 1);
    ts.push_back(t[e]);
    us.push_back(u[e]);
    return StageMotion::tabulated(std::move(ts), std::move(us));
}

}  // namespace

Prediction predictDynamics(const CleanRun& run, const RigParams& rig, const FrictionLaw& law, const PredictSettings& s) {
    Prediction pr;
    const io::Run& r = run.run;
    if (!r.has(Signal::StageDisp) || !r.has(Signal::SliderDisp) || !r.has(Signal::Friction) || !r.has(Signal::SliderVel)) {
        pr.message = r.file + ": the dynamics set-up needs stage and slider displacement and friction force";
        return pr;
    }
    const std::vector<double>& t = r[Signal::Time];
    DynamicsModel m;
    m.rig = rig;
    m.law = law;
    const long sub = std::max(1L, std::lround(run.dt_s / s.dt_s));
    m.dt_s = run.dt_s / static_cast<double>(sub);
    const std::vector<double>& U = r[Signal::StageDisp];
    const size_t segLen = std::max<size_t>(2, static_cast<size_t>(std::lround(s.segment_s / run.dt_s)));
    const size_t spacing = std::max(segLen, static_cast<size_t>(std::lround(s.segmentSpacing_s / run.dt_s)));
    const bool filtered = s.filterPrediction && !run.filter.empty();
    const size_t margin = filtered ? impulseResponseLength(run.filter) : 0;
    const std::vector<double>& Fm = r[Signal::Friction];
    const std::vector<double>& Xm = r[Signal::SliderDisp];
    // Unfiltered measurement (the filter's input) when kept, else the cleaned one.
    const std::vector<double>& Fu = filtered && run.unfilteredForce_N.size() == Fm.size() ? run.unfilteredForce_N : Fm;
    const std::vector<double>& Xu = filtered && run.unfilteredSlider_m.size() == Xm.size() ? run.unfilteredSlider_m : Xm;
    std::vector<double> dF(segLen + 1), dX(segLen + 1);  // prediction − measurement over a segment
    double threshold = 0.0;  // |V| that counts as slipping for a segment start
    if (s.slipStartFraction > 0.0 && r.has(Signal::RelVel)) {
        double vmax = 0.0;
        for (size_t i = run.begin; i < run.end; ++i) vmax = std::max(vmax, std::abs(r[Signal::RelVel][i]));
        threshold = s.slipStartFraction * vmax;
    }
    // First sample a segment may start at: the end of the previous one (its start sample is not
    // scored, so no residual sample is shared; with slipStartFraction = 0 every segment starts at
    // its nominal time, as spacing >= segment length).
    size_t next = run.begin;
    for (size_t n0 = run.begin; n0 + segLen < run.end; n0 += spacing) {
        size_t s0 = std::max(n0, next);
        if (threshold > 0.0) {
            size_t q = s0;
            while (q < n0 + spacing && q + segLen < run.end && std::abs(r[Signal::RelVel][q]) < threshold) ++q;
            if (q < n0 + spacing && q + segLen < run.end) s0 = q;
        }
        if (s0 + segLen >= run.end) break;
        next = s0 + segLen;
        m.stage = smoothStage(t, U, s0, segLen, sub);
        DynState st;
        st.t = t[s0];
        st.x = r[Signal::SliderDisp][s0];
        st.v = r[Signal::SliderVel][s0];
        st.u = m.stage.displacement(st.t);
        st.law.force_N = r[Signal::Friction][s0];
        // α in steady sliding at the measured slip rate: the law's state is not measured, and
        // it relaxes within a slip of D_c. Right when the segment starts in slip
        // (slipStartFraction > 0); while stuck the true α is frozen at its end-of-slip value.
        const double V = r.has(Signal::RelVel) ? r[Signal::RelVel][s0] : 0.0;
        st.law.alpha = std::holds_alternative<RateStateLaw>(law) ? std::get<RateStateLaw>(law).steadyStateAlpha(V) : 0.0;
        st.a = (st.law.force_N - rig.stiffness_N_per_m * st.x - rig.damping_Ns_per_m * st.v) / rig.mass_kg;
        dF[0] = st.law.force_N - Fu[s0];
        dX[0] = st.x - Xu[s0];
        for (size_t j = 1; j <= segLen; ++j) {
            const StepReport rep = advanceQuiet(m, st, sub);
            if (rep.status != RunStatus::Ok) {
                pr.message = r.file + ": " + rep.message;
                pr.ok = false;
                return pr;
            }
            dF[j] = st.law.force_N - Fu[s0 + j];
            dX[j] = st.x - Xu[s0 + j];
        }
        if (filtered) {
            dF = filtfiltZeroExtended(run.filter, dF, margin);
            dX = filtfiltZeroExtended(run.filter, dX, margin);
        }
        for (size_t j = 1; j <= segLen; ++j)
            if (j % static_cast<size_t>(s.residualStride) == 0) {
                pr.index.push_back(s0 + j);
                pr.force_N.push_back(Fm[s0 + j] + dF[j]);
                pr.slider_m.push_back(Xm[s0 + j] + dX[j]);
            }
    }
    if (pr.index.empty()) {
        pr.message = r.file + ": fit window shorter than one segment";
        return pr;
    }
    pr.ok = true;
    return pr;
}

Prediction predictRun(const CleanRun& run, SetupKind setup, const ModelSpec& spec, const PredictSettings& s) {
    SimParams p;
    std::string why;
    if (!runParams(run, spec, p, &why)) {
        Prediction pr;
        pr.message = why;
        return pr;
    }
    const FrictionLaw law = makeLaw(p);
    if (setup == SetupKind::Prescribed) return predictPrescribed(run, law, p.rig.normalForce_N, s);
    return predictDynamics(run, p.rig, law, s);
}

}  // namespace stickslip::identify
