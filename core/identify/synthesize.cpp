#include "synthesize.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "../integrate/stage_motion.hpp"

namespace stickslip::identify {

namespace {

// The five kinds of run in every shared set (their k, A, f and t_N fall into these classes, in
// shuffled order): stiff beam at small amplitude and high load, medium beam, soft beam at large
// amplitude, stiff beam at large amplitude, stiff beam near the paper's Fig. 20 run.
struct RunClass {
    double k_N_per_m;
    DrawRange A_m, tN_N;
    std::vector<double> f_Hz;
};
const std::vector<RunClass>& runClasses() {
    static const std::vector<RunClass> c = {
        {8446.0, {0.53e-3, 0.69e-3}, {10.8, 13.1}, {4.0, 5.0, 6.0}},
        {3034.0, {1.70e-3, 2.30e-3}, {3.7, 4.4}, {2.0, 2.5}},
        {1547.0, {2.60e-3, 3.40e-3}, {5.7, 6.6}, {2.5, 3.0, 4.0}},
        {8446.0, {2.16e-3, 2.90e-3}, {8.1, 9.8}, {2.5, 3.0, 4.0}},
        {8446.0, {0.86e-3, 1.14e-3}, {5.7, 6.8}, {2.5, 3.0, 4.0, 5.0}},
    };
    return c;
}

double draw(std::mt19937_64& rng, const DrawRange& r) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double q = u(rng);
    if (r.log) return std::exp(std::log(r.lo) + q * (std::log(r.hi) - std::log(r.lo)));
    return r.lo + q * (r.hi - r.lo);
}

void checkRange(ParamIssues& out, const std::string& field, const DrawRange& r) {
    const bool ok = std::isfinite(r.lo) && std::isfinite(r.hi) && r.lo <= r.hi && (!r.log || r.lo > 0.0);
    if (!ok) out.push_back({field, r.lo, r.log ? "0 < lo <= hi, finite" : "lo <= hi, finite"});
}

// Mains pickup of one channel: 60 Hz and 180 Hz of random amplitude and phase.
struct Pickup {
    double a60 = 0, p60 = 0, a180 = 0, p180 = 0;
    double at(double t) const {
        return a60 * std::sin(2 * M_PI * 60.0 * t + p60) + a180 * std::sin(2 * M_PI * 180.0 * t + p180);
    }
};

Pickup drawPickup(std::mt19937_64& rng, const SynthRanges& r) {
    std::uniform_real_distribution<double> ph(0.0, 2 * M_PI);
    Pickup p;
    p.a60 = draw(rng, r.mains60_N);
    p.p60 = ph(rng);
    p.a180 = draw(rng, r.mains180_N);
    p.p180 = ph(rng);
    return p;
}

void drawBaseline(std::mt19937_64& rng, const SynthRanges& r, ExtendedModel& m, double& zeta) {
    m.law.mu = draw(rng, r.mu);
    m.law.C1 = draw(rng, r.C1);
    m.law.r = 1.0;
    m.law.Dc_m = draw(rng, r.Dc_m);
    m.law.eta_s_per_m = draw(rng, r.eta_s_per_m);
    m.law.vc_mps = draw(rng, r.vc_mps);
    m.law.epsT_N_per_m = draw(rng, r.epsT_N_per_m);
    m.rig.mass_kg = draw(rng, r.mass_kg);
    zeta = draw(rng, r.zeta);
    m.tNref_N = 6.2;
    // The independent simulator's discretisation: backward Euler in the law at a fine step.
    m.stateStep = StateStep::BackwardEuler;
}

// Simulates one run (transient + record) and samples it; false with a message on failure.
bool simulateRun(const SynthOptions& o, const ExtendedModel& truth, double zeta, double transient_s, std::mt19937_64& rng,
                 SynthRun& run, std::string& message) {
    ExtendedModel m = truth;
    m.rig.stiffness_N_per_m = run.k_N_per_m;
    m.rig.normalForce_N = run.tN_N;
    m.rig.damping_Ns_per_m = dampingFromRatio(zeta, run.k_N_per_m, m.rig.mass_kg);
    DriveParams d;
    d.amplitude_m = run.A_m;
    d.frequency_Hz = run.f_Hz;
    const StageMotion stage = StageMotion::harmonic(d);
    const long skip = std::lround(transient_s * o.sampleRate_Hz);
    const long samples = std::lround(o.seconds * o.sampleRate_Hz);
    const double dt = 1.0 / (o.sampleRate_Hz * o.stepsPerSample);
    RunContext ctx;
    ctx.normalForce_N = run.tN_N;
    ctx.accumulatedSlipStart_m = run.slipStart_m;
    const ExtendedTrace tr = simulateExtendedDynamics(m, ctx, stage, 0.0, dt, (skip + samples - 1) * o.stepsPerSample,
                                                      o.stepsPerSample);
    if (!tr.ok()) {
        message = run.file + ": " + tr.message;
        return false;
    }
    run.slipEnd_m = tr.accumulatedSlipEnd_m;
    std::normal_distribution<double> nd(0.0, 1.0);
    const Pickup pf = drawPickup(rng, o.ranges), pn = drawPickup(rng, o.ranges);
    for (long i = skip; i < skip + samples && i < static_cast<long>(tr.t_s.size()); ++i) {
        const double t = static_cast<double>(i - skip) / o.sampleRate_Hz;
        const size_t k = static_cast<size_t>(i);
        run.t_s.push_back(t);
        const double s = o.noiseScale;
        run.stage_m.push_back(tr.stage_m[k] + s * o.dispNoise_m * nd(rng));
        run.slider_m.push_back(tr.slider_m[k] + s * o.dispNoise_m * nd(rng));
        run.force_N.push_back(tr.measuredForce_N[k] + s * (o.forceNoise_N * nd(rng) + pf.at(t)));
        run.normal_N.push_back(run.tN_N + s * (o.forceNoise_N * nd(rng) + pn.at(t)));
        run.accel_mps2.push_back(tr.sliderAccel_mps2[k] + s * o.accelNoise_mps2 * nd(rng));
    }
    return true;
}

nlohmann::json lawJson(const ExtendedModel& m, double zeta) {
    return {{"m", m.rig.mass_kg}, {"zeta", zeta},        {"mu", m.law.mu},   {"C1", m.law.C1},
            {"r", m.law.r},       {"Dc", m.law.Dc_m},    {"eta", m.law.eta_s_per_m},
            {"vc", m.law.vc_mps}, {"epsT", m.law.epsT_N_per_m}};
}

}  // namespace

ParamIssues SynthOptions::validate() const {
    ParamIssues out;
    if (runs < 1 || runs > static_cast<int>(runClasses().size())) out.push_back({"runs", double(runs), "1 ... 5"});
    if (!(seconds > 0.0 && seconds <= 3600.0)) out.push_back({"seconds", seconds, "> 0 and <= 3600"});
    if (!(sampleRate_Hz >= 100.0 && sampleRate_Hz <= 1e5)) out.push_back({"sample_rate", sampleRate_Hz, "100 ... 100000 Hz"});
    if (stepsPerSample < 1 || stepsPerSample > 10000) out.push_back({"steps_per_sample", double(stepsPerSample), "1 ... 10000"});
    const std::pair<const char*, double> noises[] = {
        {"disp_noise", dispNoise_m}, {"force_noise", forceNoise_N}, {"accel_noise", accelNoise_mps2}};
    for (const auto& [f, v] : noises)
        if (!(v >= 0.0 && std::isfinite(v))) out.push_back({f, v, ">= 0, finite"});
    if (!(noiseScale >= 0.0 && noiseScale <= 100.0)) out.push_back({"noise_scale", noiseScale, "0 ... 100"});
    if (!(nominalMass_kg > 0.0 && std::isfinite(nominalMass_kg))) out.push_back({"nominal_mass", nominalMass_kg, "> 0"});
    const std::pair<const char*, DrawRange> rs[] = {
        {"ranges.mass", ranges.mass_kg}, {"ranges.zeta", ranges.zeta}, {"ranges.mu", ranges.mu},
        {"ranges.C1", ranges.C1}, {"ranges.Dc", ranges.Dc_m}, {"ranges.eta", ranges.eta_s_per_m},
        {"ranges.vc", ranges.vc_mps}, {"ranges.epsT", ranges.epsT_N_per_m}, {"ranges.mains60", ranges.mains60_N},
        {"ranges.mains180", ranges.mains180_N}, {"ranges.transient", ranges.transient_s}};
    for (const auto& [f, r] : rs) checkRange(out, f, r);
    for (const auto& [name, values] : effects) {
        EffectInfo info;
        if (!findEffect(name, info)) {
            out.push_back(ParamIssue::note("effect", "unknown effect '" + name + "'"));
            continue;
        }
        if (values.size() != info.params.size()) {
            out.push_back(ParamIssue::note("effect", name + " takes " + std::to_string(info.params.size()) +
                                                         " parameter(s), got " + std::to_string(values.size())));
            continue;
        }
        for (size_t i = 0; i < values.size(); ++i) {
            const EffectParam& p = info.params[i];
            if (!(values[i] >= p.lower && values[i] <= p.upper))
                out.push_back({name + "." + p.name, values[i],
                               std::to_string(p.lower) + " ... " + std::to_string(p.upper) + " " + p.unit});
        }
    }
    return out;
}

SynthResult synthesizeRigSet(const SynthOptions& o) {
    SynthResult res;
    if (const ParamIssues is = o.validate(); !is.empty()) {
        res.message = formatIssues(is);
        return res;
    }
    std::mt19937_64 rng(o.seed);
    ExtendedModel& m = res.truth;
    drawBaseline(rng, o.ranges, m, res.zeta);
    for (const auto& [name, values] : o.effects) setEffect(m.effects, name, values);
    std::vector<RunClass> classes = runClasses();
    std::shuffle(classes.begin(), classes.end(), rng);
    classes.resize(static_cast<size_t>(o.runs));
    double slip = 0.0;
    nlohmann::json mruns = nlohmann::json::array(), aruns = nlohmann::json::array();
    for (size_t i = 0; i < classes.size(); ++i) {
        const RunClass& c = classes[i];
        SynthRun run;
        char name[32];
        std::snprintf(name, sizeof name, "run_%02zu.csv", i + 1);
        run.file = name;
        run.k_N_per_m = c.k_N_per_m;
        run.A_m = draw(rng, c.A_m);
        run.tN_N = draw(rng, c.tN_N);
        run.f_Hz = c.f_Hz[std::uniform_int_distribution<size_t>(0, c.f_Hz.size() - 1)(rng)];
        run.slipStart_m = slip;
        const double transient = draw(rng, o.ranges.transient_s);
        if (!simulateRun(o, m, res.zeta, transient, rng, run, res.message)) return res;
        slip = run.slipEnd_m;
        mruns.push_back({{"file", run.file}, {"k_N_per_m", run.k_N_per_m}, {"A_m", run.A_m}, {"f_Hz", run.f_Hz},
                         {"tN_N", run.tN_N}, {"duration_s", o.seconds}});
        aruns.push_back({{"file", run.file}, {"transient_s", transient}, {"accumulated_slip_start_m", run.slipStart_m},
                         {"accumulated_slip_end_m", run.slipEnd_m}});
        res.runs.push_back(std::move(run));
    }
    res.manifest = {{"sampling_rate_Hz", o.sampleRate_Hz},
                    {"columns", {"time_s", "stage_disp_m", "slider_disp_m", "friction_force_N", "normal_force_N",
                                 "slider_accel_mps2"}},
                    {"nominal_mass_kg", o.nominalMass_kg},
                    {"notes", "stickslip-cli synthesize: k, A, f and tN per run; runs recorded in file order on one specimen"},
                    {"runs", mruns}};
    nlohmann::json eff = nlohmann::json::object();
    for (const auto& [name, values] : o.effects) {
        EffectInfo info;
        findEffect(name, info);
        nlohmann::json p = nlohmann::json::object();
        for (size_t i = 0; i < values.size(); ++i) p[info.params[i].name] = values[i];
        eff[name] = p;
    }
    nlohmann::json names = nlohmann::json::array();
    for (const auto& e : o.effects) names.push_back(e.first);
    res.answer = {{"seed", o.seed},
                  {"effects", names},
                  {"effect_params", eff},
                  {"baseline_params", lawJson(m, res.zeta)},
                  {"tN_ref_N", m.tNref_N},
                  {"model", "StickSlip Lab extended law (backward Euler return map + Newmark), h = 1/(" +
                                std::to_string(o.stepsPerSample) + " x sample rate)"},
                  {"noise", {{"disp_m", o.noiseScale * o.dispNoise_m}, {"force_N", o.noiseScale * o.forceNoise_N}, {"accel_mps2", o.noiseScale * o.accelNoise_mps2}, {"scale", o.noiseScale}}},
                  {"runs", aruns}};
    res.ok = true;
    return res;
}

std::string synthRunCsv(const SynthRun& r) {
    std::string s = "time_s,stage_disp_m,slider_disp_m,friction_force_N,normal_force_N,slider_accel_mps2\n";
    s.reserve(s.size() + r.t_s.size() * 72);
    char line[160];
    for (size_t i = 0; i < r.t_s.size(); ++i) {
        std::snprintf(line, sizeof line, "%.4f,%.6e,%.6e,%.6e,%.6e,%.6e\n", r.t_s[i], r.stage_m[i], r.slider_m[i],
                      r.force_N[i], r.normal_N[i], r.accel_mps2[i]);
        s += line;
    }
    return s;
}

}  // namespace stickslip::identify
