// The simulated null (IdentifyOptions::simulatedNullReplicas, selection test 4): a parametric
// bootstrap through the whole chain. The linearised noise null (noise_null.hpp) adds noise to the
// cleaned residual; it cannot know what the cleaning filters and the noise through them into the
// equation error's inputs (ẍ, V, g from filtered displacements) do to a model that lacks nothing.
// Here the current model is simulated over each fit run's recorded drive, given the recording's
// own noise, and the replica goes through the caller's cleaning (IdentifyOptions::reprepare),
// preparation and fits exactly as the data did.
#include <algorithm>
#include <cmath>
#include <random>

#include "../dsp/fourier.hpp"
#include "../dsp/sampling.hpp"
#include "../dsp/stats.hpp"
#include "../integrate/stage_motion.hpp"
#include "effects/registry.hpp"
#include "identify_internal.hpp"
#include "simulated_null.hpp"

namespace stickslip::identify::detail {

using io::Signal;

namespace {

constexpr double kPreroll_s = 3.0;   // simulated before the recording starts (the rig's transient)
constexpr int kStageOrder = 5;       // harmonics of the drive's fit (PreprocessSettings' default)
constexpr int kMainsHarmonics = 3;   // mains pickup at f, 2f, 3f (60/120/180 Hz)

// The drive frequency of a recording: the run's, else its stated setting, else the stage's period.
double driveFrequency(const IdentifyRun& run, const io::Run& rec) {
    if (run.frequency_Hz > 0) return run.frequency_Hz;
    double f = 0;
    if (rec.setting("f", f) && f > 0) return f;
    const double T = dsp::estimatePeriod(rec[Signal::Time], rec[Signal::StageDisp]);
    return T > 0 ? 1.0 / T : 0.0;
}

}  // namespace

bool replicaRecording(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals,
                      const IdentifyRun& run, uint64_t seed, io::Run& out, std::string& why) {
    if (!run.recording) {
        why = run.file + ": the recording is not available";
        return false;
    }
    const io::Run& rec = *run.recording;
    if (!rec.has(Signal::Time) || !rec.has(Signal::StageDisp) || !rec.has(Signal::SliderDisp) ||
        !rec.has(Signal::Friction) || rec.size() < 16) {
        why = run.file + ": a replica needs the recorded time, stage and slider displacement and friction force";
        return false;
    }
    const std::vector<double>& t = rec[Signal::Time];
    const size_t n = t.size();
    const double dt = (t.back() - t.front()) / static_cast<double>(n - 1);
    const double f0 = driveFrequency(run, rec);
    if (!(dt > 0) || !(f0 > 0)) {
        why = run.file + ": no sampling step or drive frequency for a replica";
        return false;
    }
    // The drive: the stage's harmonic fit, defined before the recording too (the pre-roll).
    const double fr = dsp::refineFrequency(t, rec[Signal::StageDisp], f0, kStageOrder);
    const dsp::HarmonicFit drive = dsp::harmonicFit(t, rec[Signal::StageDisp], fr, kStageOrder, 0, n);
    const size_t pre = static_cast<size_t>(std::ceil(kPreroll_s / dt));
    std::vector<double> tt(pre + n), uu(pre + n);
    for (size_t k = 0; k < tt.size(); ++k) {
        tt[k] = t.front() + (static_cast<double>(k) - static_cast<double>(pre)) * dt;
        uu[k] = drive.at(tt[k]);
    }
    ParamIssues bad;
    const std::optional<StageMotion> stage = StageMotion::tabulated(tt, uu, &bad);
    if (!stage) {
        why = run.file + ": replica drive: " + formatIssues(bad);
        return false;
    }
    double mass = kNaN;
    ExtendedModel m = buildModel(cx, spec, vals, mass);
    m.rig.stiffness_N_per_m = run.stiffness_N_per_m;
    m.rig.mass_kg = std::isfinite(mass) ? mass : run.nominalMass_kg;
    m.rig.normalForce_N = run.normalForce_N;
    m.rig.damping_Ns_per_m = 2.0 * cx.opt->zetaNominal * std::sqrt(m.rig.stiffness_N_per_m * m.rig.mass_kg);
    const int sub = std::max(1, cx.opt->simulatedNullStepsPerSample);
    RunControl ctl;
    ctl.cancel = cx.opt->cancel;
    const ExtendedTrace tr = simulateExtendedDynamics(m, RunContext{run.normalForce_N, run.slipBefore_m}, *stage, tt.front(),
                                                      dt / sub, static_cast<long>(pre + n - 1) * sub, sub, ctl);
    if (!tr.ok() || tr.t_s.size() != pre + n) {
        why = run.file + ": replica simulation: " + (tr.ok() ? std::string("short trace") : tr.message);
        return false;
    }
    // Noise as the recording has it: white at the level of its third differences, and on the force
    // the mains pickup (harmonics of the band-stop's centre) fitted to the recorded force.
    std::vector<double> pickup(n, 0.0);
    if (run.filtered && run.filters.bandStop) {
        const dsp::HarmonicFit mains =
            dsp::harmonicFit(t, rec[Signal::Friction], run.filters.bandStopCenter_Hz, kMainsHarmonics, 0, n);
        for (size_t i = 0; i < n; ++i) pickup[i] = mains.at(t[i]) - mains.mean;
    }
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> nd(0.0, 1.0);
    out = rec;
    auto replace = [&](Signal s, const std::vector<double>& clean, const std::vector<double>* extra) {
        if (!rec.has(s)) return;
        const double sigma = dsp::whiteNoiseRms(rec[s]);
        std::vector<double>& y = out[s];
        for (size_t i = 0; i < n; ++i) y[i] = clean[pre + i] + sigma * nd(rng) + (extra ? (*extra)[i] : 0.0);
    };
    replace(Signal::SliderDisp, tr.slider_m, nullptr);
    replace(Signal::Friction, tr.measuredForce_N, &pickup);
    replace(Signal::SliderAccel, tr.sliderAccel_mps2, nullptr);
    replace(Signal::SliderVel, tr.sliderVel_mps, nullptr);
    replace(Signal::RelVel, tr.relVel_mps, nullptr);
    if (rec.has(Signal::Slip))
        for (size_t i = 0; i < n; ++i) out[Signal::Slip][i] = out[Signal::StageDisp][i] - out[Signal::SliderDisp][i];
    return true;
}

namespace {

// The fit runs' replicas from (spec, vals), cleaned and prepared as the data were; `reps` owns the
// runs `rc` points to. False with `why`.
bool replicaContext(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals,
                    const std::vector<size_t>& fitIdx, uint64_t seed, std::vector<IdentifyRun>& reps, Context& rc,
                    std::string& why) {
    reps.assign(fitIdx.size(), IdentifyRun{});
    for (size_t k = 0; k < fitIdx.size(); ++k) {
        io::Run rec;
        if (!replicaRecording(cx, spec, vals, *cx.runs[fitIdx[k]].run, seed + k, rec, why) ||
            !cx.opt->reprepare(rec, reps[k], why))
            return false;
        reps[k].validation = false;
    }
    int dec = 0;
    if (!prepareContext(reps, *cx.opt, rc, dec, why)) return false;
    // The data's wear history and load reference, not the replica's subset's.
    for (size_t k = 0; k < fitIdx.size(); ++k) reps[k].slipBefore_m = cx.runs[fitIdx[k]].run->slipBefore_m;
    rc.tNref = cx.tNref;
    rc.muScale = cx.muScale;
    return true;
}

}  // namespace

SimulatedNull simulatedGainNull(const Context& cx, const Spec& cur, const std::map<std::string, double>& curVals,
                                const Spec& cand, const std::map<std::string, double>& candVals,
                                const std::vector<size_t>& fitIdx, int replicas, uint64_t seed, long& fits) {
    SimulatedNull out;
    const IdentifyOptions& opt = *cx.opt;
    if (!opt.reprepare) {
        out.note = "not run: the runs were given cleaned, without their recordings";
        return out;
    }
    for (size_t i : fitIdx)
        if (cx.runs[i].run->setup != SetupKind::Dynamics || !cx.runs[i].run->recording) {
            out.note = "not run: only spring-mass (dynamics) runs with their recordings have replicas";
            return out;
        }
    std::vector<size_t> idx(fitIdx.size());
    for (size_t k = 0; k < idx.size(); ++k) idx[k] = k;
    const std::string effect = cand.effects.empty() ? std::string() : cand.effects.back();
    std::map<std::string, double> model = curVals;
    // A replica of the fit runs from `model`; false, with out.note saying why, when cancelled or
    // when it cannot be made.
    auto replica = [&](uint64_t sd, std::vector<IdentifyRun>& reps, Context& rc) {
        if (opt.cancelRequested()) {
            out.note = "cancelled";
            return false;
        }
        std::string why;
        if (replicaContext(cx, cur, model, fitIdx, sd, reps, rc, why)) return true;
        out.note = "not run: " + why;
        return false;
    };
    // (a) The fit's own bias: replicas of the fitted model, refitted. The cleaning biases the
    // equation-error fit (a noise-free set refits C1 0.26 -> 2.0), and replicas of the biased model
    // lack what the data have (the data's false sensor mass gained 0.79, replicas of the fitted
    // model 0.02-0.12, replicas of the true model 0.58-0.91; docs/identify-results.md, session 41).
    // Indirect inference (IdentifyOptions::simulatedNullBiasSteps fixed-point steps) moves the
    // replicas' model until their fits land where the data's did: in log scale for the positive
    // parameters, clamped to their ranges.
    const int biasReplicas = std::max(2, replicas / 2);
    const std::vector<FitParameter> ps = parameters(cx, cur, curVals);
    for (int step = 0; step < std::max(0, opt.simulatedNullBiasSteps); ++step) {
        std::map<std::string, std::vector<double>> refit;
        for (int b = 0; b < biasReplicas; ++b) {
            std::vector<IdentifyRun> reps;
            Context rc;
            if (!replica(seed + 7777777u * static_cast<uint64_t>(step + 1) + 1000003u * static_cast<uint64_t>(b), reps, rc))
                return out;
            const FitOutcome f = fitSpec(rc, cur, curVals, idx, 1, fits, false, FitStart::NearOptimum);
            if (!f.ok) continue;
            for (const auto& [k, v] : f.values) refit[k].push_back(v);
        }
        // Fixed-point step towards the model whose replicas' fits land on the data's fit.
        for (const FitParameter& fp : ps) {
            const auto it = refit.find(fp.name);
            if (!fp.free || it == refit.end() || it->second.size() < 2) continue;
            const double target = curVals.at(fp.name), now = model.at(fp.name);
            bool positive = target > 0 && now > 0;
            for (double v : it->second) positive = positive && v > 0;
            double mean = 0;
            for (double v : it->second) mean += (positive ? std::log(v) : v) / static_cast<double>(it->second.size());
            const double next = positive ? std::exp(std::log(now) + std::log(target) - mean) : now + target - mean;
            model[fp.name] = std::clamp(next, fp.lower, fp.upper);
        }
    }
    out.model = model;
    // (b) The null: replicas of the corrected model; the current model and the candidate refitted
    // from their fits to the data (the candidate from the replica's current fit with the effect as
    // the data gave it).
    for (int b = 0; b < replicas; ++b) {
        std::vector<IdentifyRun> reps;
        Context rc;
        if (!replica(seed + 1000003u * static_cast<uint64_t>(b), reps, rc)) return out;
        const FitOutcome f0 = fitSpec(rc, cur, curVals, idx, 1, fits, false, FitStart::NearOptimum);
        if (!f0.ok) {
            out.note = "not run: a replica's fit failed (" + f0.message + ")";
            return out;
        }
        std::map<std::string, double> start = f0.values;
        for (const auto& [k, v] : candVals)
            if (!effect.empty() && k.rfind(effect + ".", 0) == 0) start[k] = v;
        const FitOutcome f1 = fitSpec(rc, cand, start, idx, 1, fits, false, FitStart::NearOptimum);
        out.gains.push_back(f1.ok ? std::max(0.0, f0.ss - f1.ss) : 0.0);
    }
    std::sort(out.gains.begin(), out.gains.end());
    out.ran = !out.gains.empty();
    return out;
}

}  // namespace stickslip::identify::detail
