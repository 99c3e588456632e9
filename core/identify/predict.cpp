#include "predict.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "../dsp/iir.hpp"
#include "../integrate/dynamics.hpp"
#include "../integrate/prescribed.hpp"

namespace stickslip::identify {

using io::Signal;

ParamIssues PredictSettings::validate() const {
    ParamIssues v;
    auto note = [&](const char* field, std::string text) { v.push_back(ParamIssue::note(field, std::move(text))); };
    if (stride < 1) note("stride", "stride = " + std::to_string(stride) + " must be >= 1");
    if (substeps < 1) note("substeps", "substeps = " + std::to_string(substeps) + " must be >= 1");
    if (warmup_s < 0) note("warmup", "warmup must be >= 0 s");
    if (!(dt_s > 0)) note("dt", "dt must be > 0 s");
    if (!(segment_s > 0)) note("segment", "segment length must be > 0 s");
    if (!(segmentSpacing_s >= segment_s)) note("segment_spacing", "segment spacing must be >= segment length");
    if (residualStride < 1) note("residual_stride", "residual stride must be >= 1");
    if (initialStateIterations < 1 || initialStateIterations > 20)
        note("initial_state_iterations",
             "initial-state iterations = " + std::to_string(initialStateIterations) + " must be in [1, 20]");
    if (!(slipStartFraction >= 0.0 && slipStartFraction < 1.0))
        note("slip_start_fraction", "slip start fraction = " + std::to_string(slipStartFraction) + " must be in [0, 1)");
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
    if (spec.tieC1ToMu && !spec.values.count("C1")) p.lawParams<RateStateParams>().C1 = p.lawParams<RateStateParams>().mu;
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
        d = dsp::filtfiltZeroExtended(run.filter, d);
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
// No motion (and `issues` set) when the run's time column does not increase strictly there.
std::optional<StageMotion> smoothStage(const std::vector<double>& t, const std::vector<double>& u, size_t s0, size_t len,
                                       long sub, ParamIssues* issues) {
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
    return StageMotion::tabulated(std::move(ts), std::move(us), issues);
}

// Segment starts of a run (from the data only, so the residual layout does not depend on the
// parameters). First sample a segment may start at: the end of the previous one (its start
// sample is not scored, so no residual sample is shared; with slipStartFraction = 0 every
// segment starts at its nominal time, as spacing >= segment length). With slipStartFraction > 0
// a segment starts at the first sample within its spacing that slips faster than that fraction
// of the run's peak |V|.
std::vector<size_t> segmentStarts(const CleanRun& run, const PredictSettings& s, size_t segLen, size_t spacing) {
    const io::Run& r = run.run;
    double threshold = 0.0;  // |V| that counts as slipping for a segment start
    if (s.slipStartFraction > 0.0 && r.has(Signal::RelVel)) {
        double vmax = 0.0;
        for (size_t i = run.begin; i < run.end; ++i) vmax = std::max(vmax, std::abs(r[Signal::RelVel][i]));
        threshold = s.slipStartFraction * vmax;
    }
    std::vector<size_t> starts;
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
        starts.push_back(s0);
    }
    return starts;
}

// One segment of a run simulated from an initial slider state: eF, eX = prediction − unfiltered
// measurement on samples s0 … s0 + segLen, through the run's filter (zero-phase, zero-extended
// by its impulse response) when the prediction is filtered. The stage motion is `m.stage`.
struct SegmentSimulator {
    DynamicsModel& m;
    const CleanRun& run;
    const FrictionLaw& law;
    const std::vector<double>& Fm;
    const std::vector<double>& Fu;  // unfiltered measurement (the filter's input) when kept, else Fm
    const std::vector<double>& Xu;
    size_t segLen;
    long sub;  // steps per sample
    bool filtered;
    size_t margin;
    std::string failure;

    bool operator()(size_t s0, double x0, double v0, std::vector<double>& eF, std::vector<double>& eX) {
        const io::Run& r = run.run;
        const std::vector<double>& t = r[Signal::Time];
        DynState st;
        st.t = t[s0];
        st.x = x0;
        st.v = v0;
        st.u = m.stage.displacement(st.t);
        st.law.force_N = Fm[s0];
        // α in steady sliding at the measured slip rate: the law's state is not measured, and
        // it relaxes within a slip of D_c. Right when the segment starts in slip
        // (slipStartFraction > 0); while stuck the true α is frozen at its end-of-slip value.
        const double V = r.has(Signal::RelVel) ? r[Signal::RelVel][s0] : 0.0;
        st.law.alpha = steadyStateAlpha(law, V);
        st.a = (st.law.force_N - m.rig.stiffness_N_per_m * st.x - m.rig.damping_Ns_per_m * st.v) / m.rig.mass_kg;
        eF.assign(segLen + 1, 0.0);
        eX.assign(segLen + 1, 0.0);
        eF[0] = st.law.force_N - Fu[s0];
        eX[0] = st.x - Xu[s0];
        for (size_t j = 1; j <= segLen; ++j) {
            const StepReport rep = advanceQuiet(m, st, sub);
            if (rep.status != RunStatus::Ok) {
                failure = r.file + ": " + rep.message;
                return false;
            }
            eF[j] = st.law.force_N - Fu[s0 + j];
            eX[j] = st.x - Xu[s0 + j];
        }
        if (filtered) {
            eF = dsp::filtfiltZeroExtended(run.filter, eF, margin);
            eX = dsp::filtfiltZeroExtended(run.filter, eX, margin);
        }
        return true;
    }
};

// Weights of the initial-state projection: each channel divided by the RMS of its measurement
// over every scored sample of the run (the weighting of fitDataset), and the RMS of ẋ (the
// scale of v0's difference step).
struct StateWeights {
    double wF = 1.0, wX = 1.0, sV = 0.0;
};
StateWeights initialStateWeights(const CleanRun& run, const std::vector<size_t>& starts, size_t segLen, size_t rstride) {
    const io::Run& r = run.run;
    const std::vector<double>& Fm = r[Signal::Friction];
    const std::vector<double>& Xm = r[Signal::SliderDisp];
    const std::vector<double>& Vm = r[Signal::SliderVel];
    double sf = 0, sx = 0, sv = 0;
    size_t n = 0;
    for (size_t s0 : starts)
        for (size_t j = rstride; j <= segLen; j += rstride) {
            sf += Fm[s0 + j] * Fm[s0 + j];
            sx += Xm[s0 + j] * Xm[s0 + j];
            sv += Vm[s0 + j] * Vm[s0 + j];
            ++n;
        }
    const double dn = static_cast<double>(std::max<size_t>(n, 1));
    StateWeights w;
    w.wF = 1.0 / std::max(std::sqrt(sf / dn), 1e-12);
    w.wX = 1.0 / std::max(std::sqrt(sx / dn), 1e-15);
    w.sV = std::sqrt(sv / dn);
    return w;
}

// The segment's initial state (x0, v0) as a nuisance parameter (variable projection, see
// PredictSettings): Gauss–Newton on (x0, v0) from the measured state, with forward-difference
// sensitivities in coordinates scaled by the run's RMS of x and ẋ. Every step is taken (no
// accept/reject test: the profiled residual must be a smooth function of the law parameters
// for the outer numeric Jacobian), and the last one is not simulated again: dF, dX (on entry the
// residual from the measured state) become its linear model e + J δ, i.e. the residual
// projected off the two initial-state directions. A tiny Levenberg term keeps a direction the
// segment hardly sees (ẋ0 of a segment that stays stuck) finite. False (sim.failure) when a
// simulation fails.
bool projectInitialState(SegmentSimulator& sim, size_t s0, double x0, double v0, const StateWeights& w, int iterations,
                         size_t rstride, std::vector<double>& dF, std::vector<double>& dX) {
    const size_t segLen = sim.segLen;
    std::vector<double> pF, pX, qF, qX;  // displaced and trial trajectories
    const double sx = 1.0 / w.wX, sv = std::max(w.sV, 1e-12);
    constexpr double kRel = 1e-3;  // difference step, in units of sx, sv
    for (int it = 0; it < iterations; ++it) {
        if (!sim(s0, x0 + kRel * sx, v0, pF, pX) || !sim(s0, x0, v0 + kRel * sv, qF, qX)) return false;
        double A11 = 0, A12 = 0, A22 = 0, g1 = 0, g2 = 0;
        for (size_t j = rstride; j <= segLen; j += rstride) {
            const double e[2] = {dF[j] * w.wF, dX[j] * w.wX};
            const double jx[2] = {(pF[j] - dF[j]) * w.wF / kRel, (pX[j] - dX[j]) * w.wX / kRel};  // de/d(δx/sx)
            const double jv[2] = {(qF[j] - dF[j]) * w.wF / kRel, (qX[j] - dX[j]) * w.wX / kRel};  // de/d(δv/sv)
            for (int c = 0; c < 2; ++c) {
                A11 += jx[c] * jx[c];
                A12 += jx[c] * jv[c];
                A22 += jv[c] * jv[c];
                g1 += jx[c] * e[c];
                g2 += jv[c] * e[c];
            }
        }
        const double damp = 1e-6 * (A11 + A22) + 1e-300;
        A11 += damp;
        A22 += damp;
        const double det = A11 * A22 - A12 * A12;
        const double da = det > 0 ? -(A22 * g1 - A12 * g2) / det : 0.0;
        const double db = det > 0 ? -(A11 * g2 - A12 * g1) / det : 0.0;
        if (it + 1 == iterations) {
            for (size_t j = rstride; j <= segLen; j += rstride) {
                dF[j] += ((pF[j] - dF[j]) * da + (qF[j] - dF[j]) * db) / kRel;
                dX[j] += ((pX[j] - dX[j]) * da + (qX[j] - dX[j]) * db) / kRel;
            }
            break;
        }
        x0 += da * sx;
        v0 += db * sv;
        if (!sim(s0, x0, v0, dF, dX)) return false;
    }
    return true;
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
    const size_t rstride = static_cast<size_t>(s.residualStride);
    const bool filtered = s.filterPrediction && !run.filter.empty();
    const size_t margin = filtered ? dsp::impulseResponseLength(run.filter) : 0;
    const std::vector<double>& Fm = r[Signal::Friction];
    const std::vector<double>& Xm = r[Signal::SliderDisp];
    const std::vector<double>& Vm = r[Signal::SliderVel];
    // Unfiltered measurement (the filter's input) when kept, else the cleaned one.
    const std::vector<double>& Fu = filtered && run.unfilteredForce_N.size() == Fm.size() ? run.unfilteredForce_N : Fm;
    const std::vector<double>& Xu = filtered && run.unfilteredSlider_m.size() == Xm.size() ? run.unfilteredSlider_m : Xm;
    const std::vector<size_t> starts = segmentStarts(run, s, segLen, spacing);
    if (starts.empty()) {
        pr.message = r.file + ": fit window shorter than one segment";
        return pr;
    }
    SegmentSimulator sim{m, run, law, Fm, Fu, Xu, segLen, sub, filtered, margin, {}};
    const StateWeights w = s.fitInitialState ? initialStateWeights(run, starts, segLen, rstride) : StateWeights{};
    std::vector<double> dF(segLen + 1), dX(segLen + 1);
    for (size_t s0 : starts) {
        ParamIssues stageIssues;
        std::optional<StageMotion> stage = smoothStage(t, U, s0, segLen, sub, &stageIssues);
        if (!stage) {
            pr.message = r.file + ": stage motion of the segment at t = " + std::to_string(t[s0]) + " s: " + formatIssues(stageIssues);
            return pr;
        }
        m.stage = std::move(*stage);
        if (!sim(s0, Xm[s0], Vm[s0], dF, dX)) {
            pr.message = sim.failure;
            return pr;
        }
        if (s.fitInitialState) {
            if (!projectInitialState(sim, s0, Xm[s0], Vm[s0], w, s.initialStateIterations, rstride, dF, dX)) {
                pr.message = sim.failure;
                return pr;
            }
            pr.nuisanceParameters += 2;
        }
        for (size_t j = rstride; j <= segLen; j += rstride) {
            pr.index.push_back(s0 + j);
            pr.force_N.push_back(Fm[s0 + j] + dF[j]);
            pr.slider_m.push_back(Xm[s0 + j] + dX[j]);
        }
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
