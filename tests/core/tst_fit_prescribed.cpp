// Prescribed-slip fits (paper Fig. 15a): on runs made with this project's own law (no hidden
// effect) plus force noise, the parameters come back within the reported standard errors; the
// Coulomb law cannot follow the rate dependence; time splits partition the window; and a
// real damper run is fitted to a physically sensible level. Below the fits: the SimParams of a
// run (runParams), the prescribed-slip prediction at the parameters that made a run
// (predictPrescribed, predictRun) and the per-run error score (scoreRun).
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "core/identify/fit.hpp"
#include "core/integrate/prescribed.hpp"

using namespace stickslip;
using namespace stickslip::identify;
using io::Signal;

namespace {

RateStateParams truthLaw() {
    RateStateParams p;
    p.mu = 0.4; p.C1 = 0.4; p.eta_s_per_m = 2.0; p.Dc_m = 50e-6; p.vc_mps = 0.05; p.epsT_N_per_m = 2e5;
    return p;
}

// Slip g = A sin(2π f t) sampled at 1 kHz; force from the law (fine steps) plus white noise
// (0.05 N unless given; 0: the law's force exactly).
CleanRun measuredPrescribed(double A, double f, double tN, uint64_t seed, bool filters = false, double noise_N = 0.05) {
    const RateStateParams law = truthLaw();
    DriveParams d;
    d.amplitude_m = A;
    d.frequency_Hz = f;
    const SlipHistory h = SlipHistory::harmonic(d, 6.0, 1e-3);
    const RunResult r = simulatePrescribed(FrictionLaw{RateStateLaw{law}}, tN, h, 8);
    if (!r.ok()) qFatal("%s", r.message.c_str());
    io::Run run;
    run.file = "prescribed_A" + std::to_string(A * 1e3) + "mm_f" + std::to_string(f);
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> fn(0.0, noise_N > 0 ? noise_N : 1.0);
    for (size_t i = 0; i < r.samples.size(); ++i) {
        run[Signal::Time].push_back(h.t_s[i]);
        run[Signal::StageDisp].push_back(h.slip_m[i]);
        run[Signal::Friction].push_back(r.samples[i].force_N + (noise_N > 0 ? fn(rng) : 0.0));
    }
    run.settings = {{"tN", tN}, {"f", f}};
    PreprocessSettings pre;
    pre.trim.start_s = 1.0;  // the law's own start-up from F = 0
    // White noise and no mains here: filters off, so that the test checks the fit and its
    // standard errors, not the (real, small) smoothing of the stick-slip corners by the
    // 100 Hz low-pass, which biases ε_T by a few per cent (measured: 193 618 ± 613 vs 2e5).
    // (With filters on, the prediction passes through the same filter: see
    // filteredRunsRecoverTheLaw.)
    pre.filters.bandStop = filters;
    pre.filters.lowPass = filters;
    CleanRun c;
    std::string why;
    if (!preprocessRun(run, pre, c, &why)) qFatal("%s", why.c_str());
    return c;
}

// The truth law as a model specification (C1 given, so not tied to μ).
ModelSpec truthSpec() {
    const RateStateParams t = truthLaw();
    ModelSpec m;
    m.law = LawKind::RateState;
    m.tieC1ToMu = false;
    m.values = {{"mu", t.mu}, {"C1", t.C1}, {"eta", t.eta_s_per_m}, {"Dc", t.Dc_m}, {"vc", t.vc_mps}, {"epsT", t.epsT_N_per_m}};
    return m;
}

// Largest |prediction − measured force| over the predicted samples.
double worstForceError(const CleanRun& c, const Prediction& p) {
    double worst = 0;
    for (size_t k = 0; k < p.index.size(); ++k) worst = std::max(worst, std::abs(p.force_N[k] - c.run[Signal::Friction][p.index[k]]));
    return worst;
}

}  // namespace

class TstFitPrescribed : public QObject {
    Q_OBJECT
private slots:
    void recoversRateStateLawWithinStandardErrors() {
        const std::vector<CleanRun> runs = {measuredPrescribed(2e-3, 2.0, 10.0, 1), measuredPrescribed(4e-3, 3.0, 15.0, 2)};
        const std::vector<CleanRun> held = {measuredPrescribed(3e-3, 2.5, 12.0, 3)};
        DatasetFitSettings st;
        st.setup = SetupKind::Prescribed;
        st.law = LawKind::RateState;
        st.free = {"mu", "eta", "vc", "epsT"};
        st.start = {{"Dc", 50e-6}};
        st.predict.stride = 1;
        st.predict.substeps = 8;  // as the data were made: the test checks the fit, not the discretisation
        st.multistarts = 2;
        const DatasetFit f = fitDataset(runs, held, st);
        QVERIFY2(f.ok, f.message.c_str());
        qInfo("%s", f.fit.identifiabilityMessage.c_str());
        QVERIFY(f.fit.identifiable);
        const RateStateParams t = truthLaw();
        const std::map<std::string, double> want = {{"mu", t.mu}, {"eta", t.eta_s_per_m}, {"vc", t.vc_mps}, {"epsT", t.epsT_N_per_m}};
        for (const auto& [name, v] : want) {
            const double got = f.fit.value(name), se = f.fit.stderrOf(name);
            qInfo("%s = %.6g +- %.3g (true %.6g)", name.c_str(), got, se, v);
            QVERIFY(se > 0);
            QVERIFY2(std::abs(got - v) < 4 * se, name.c_str());
        }
        // The correlation matrix is a correlation matrix.
        const size_t p = f.fit.freeNames.size();
        for (size_t a = 0; a < p; ++a) {
            QVERIFY(std::abs(f.fit.correlation[a * p + a] - 1.0) < 1e-9);
            for (size_t b = 0; b < p; ++b) QVERIFY(std::abs(f.fit.correlation[a * p + b]) <= 1.0 + 1e-9);
        }
        // Only the noise is left: NRMSE ≈ 0.05 N / RMS(F); and the held-out run is predicted as well.
        qInfo("fit NRMSE %.5f validation NRMSE %.5f", f.fitNrmse, f.validationNrmse);
        QVERIFY(f.validationNrmse < 0.03);
        QCOMPARE(f.runs.size(), size_t(3));
        QCOMPARE(f.runs[2].role, std::string("validation"));

        DatasetFitSettings sc = st;
        sc.law = LawKind::Coulomb;
        sc.free = {"mu", "epsT"};
        const DatasetFit c = fitDataset(runs, held, sc);
        QVERIFY2(c.ok, c.message.c_str());
        qInfo("Coulomb: fit NRMSE %.5f validation NRMSE %.5f", c.fitNrmse, c.validationNrmse);
        QVERIFY(c.validationNrmse > 2 * f.validationNrmse);
    }

    // The same runs cleaned with the default 60 Hz band-stop and 100 Hz low-pass: since the
    // prediction passes through the identical zero-phase filter (PredictSettings::
    // filterPrediction), the law still comes back within 3 reported standard errors. Without
    // it the low-pass biased ε_T by ~30 stderr (193 618 ± 613 for 2e5, previous session).
    void filteredRunsRecoverTheLaw() {
        const std::vector<CleanRun> runs = {measuredPrescribed(2e-3, 2.0, 10.0, 1, true), measuredPrescribed(4e-3, 3.0, 15.0, 2, true)};
        QVERIFY(!runs[0].filter.empty());
        DatasetFitSettings st;
        st.setup = SetupKind::Prescribed;
        st.law = LawKind::RateState;
        st.free = {"mu", "eta", "vc", "epsT"};
        st.start = {{"Dc", 50e-6}};
        st.predict.stride = 1;
        st.predict.substeps = 8;
        st.multistarts = 1;
        const DatasetFit f = fitDataset(runs, {}, st);
        QVERIFY2(f.ok, f.message.c_str());
        QVERIFY(f.fit.identifiable);
        qInfo("tau_int = %.2f", f.tauInt);
        QVERIFY(f.tauInt >= 1.0);
        const RateStateParams t = truthLaw();
        const std::map<std::string, double> want = {{"mu", t.mu}, {"eta", t.eta_s_per_m}, {"vc", t.vc_mps}, {"epsT", t.epsT_N_per_m}};
        for (const auto& [name, v] : want) {
            const double got = f.fit.value(name), se = f.fit.stderrOf(name);
            qInfo("%s = %.6g +- %.3g (true %.6g)", name.c_str(), got, se, v);
            QVERIFY(se > 0);
            // Was 198 117 ± 571 (-3.3 stderr): the filter's edge transient on the slip (odd
            // reflection of 39 samples, settle trim of 30, vs ≈ 600 samples of band-stop memory)
            // drove the law with a slip several µm off in the last ≈ 300 samples of the window.
            QVERIFY2(std::abs(got - v) <= 3 * se, name.c_str());
        }
    }

    // The (point, run) tasks of a dataset fit may run on any number of threads: the same
    // numbers (bit for bit) on one thread as on three, and the same count of evaluations.
    void threadCountDoesNotChangeTheFit() {
        const std::vector<CleanRun> runs = {measuredPrescribed(2e-3, 2.0, 10.0, 1, true), measuredPrescribed(4e-3, 3.0, 15.0, 2, true),
                                            measuredPrescribed(1e-3, 2.0, 10.0, 3, true)};
        DatasetFitSettings st;
        st.setup = SetupKind::Prescribed;
        st.law = LawKind::RateState;
        st.free = {"mu", "eta", "vc", "epsT"};
        st.start = {{"Dc", 50e-6}};
        st.multistarts = 2;
        st.maxIterations = 8;
        st.threads = 1;
        const DatasetFit one = fitDataset(runs, {}, st);
        st.threads = 3;
        const DatasetFit three = fitDataset(runs, {}, st);
        QVERIFY2(one.ok && three.ok, (one.message + three.message).c_str());
        QVERIFY(one.fit.values == three.fit.values);
        QVERIFY(one.fit.stderrs == three.fit.stderrs);
        QVERIFY(one.fit.startCosts == three.fit.startCosts);
        QCOMPARE(one.fit.residualEvaluations, three.fit.residualEvaluations);
        QCOMPARE(one.tauInt, three.tauInt);
        QCOMPARE(one.fitNrmse, three.fitNrmse);
    }

    // simulatePrescribed prepares the law's step constants once per (Δt, t_N): bit for bit the
    // same run as calling law.returnMap step by step, also when Δt and t_N change.
    void prescribedRunEqualsStepByStepReturnMap() {
        std::vector<double> t, g, tN;
        double time = 0;
        for (int i = 0; i <= 400; ++i) {
            t.push_back(time);
            g.push_back(2e-3 * std::sin(2 * std::numbers::pi * 2.0 * time));
            tN.push_back(i < 200 ? 10.0 : 10.0 + 0.01 * (i - 200));  // constant, then varying
            time += (i % 50 < 25) ? 1e-3 : 1.3e-3;                    // two step sizes
        }
        for (const bool varying : {false, true}) {
            SlipHistory h = SlipHistory::fromSlip(t, g);
            if (varying) h.normalForce_N = tN;
            const RateStateLaw law{truthLaw()};
            const int sub = 3;
            LawState init;
            init.force_N = 0.5;
            const RunResult r = simulatePrescribed(FrictionLaw{law}, 10.0, h, sub, {}, init);
            QVERIFY2(r.ok(), r.message.c_str());
            LawState st = init;
            long stuck = 0;
            for (size_t i = 1; i < t.size(); ++i) {
                const double dt = (t[i] - t[i - 1]) / sub, dg = (g[i] - g[i - 1]) / sub;
                const double tN0 = varying ? tN[i - 1] : 10.0, tN1 = varying ? tN[i] : 10.0;
                for (int j = 1; j <= sub; ++j) {
                    const ReturnMapResult m = law.returnMap(st, dg, dt, tN0 + (tN1 - tN0) * j / sub);
                    st = m.state;
                    stuck += m.stuck ? 1 : 0;
                }
                QCOMPARE(r.samples[i].force_N, st.force_N);
                QCOMPARE(r.samples[i].alpha, st.alpha);
            }
            QCOMPARE(r.stats.stuckSteps, stuck);
            QVERIFY(stuck > 0 && stuck < r.stats.steps);  // both branches exercised
        }
    }

    void timeSplitPartitionsTheWindow() {
        const CleanRun c = measuredPrescribed(2e-3, 2.0, 10.0, 4);
        const auto [a, b] = splitByTime(c, 0.7);
        QCOMPARE(a.begin, c.begin);
        QCOMPARE(a.end, b.begin);
        QCOMPARE(b.end, c.end);
        QVERIFY(std::abs(double(a.end - a.begin) / double(c.end - c.begin) - 0.7) < 0.01);
    }

    void holdOutLaterPartsMovesEachLaterWindowToValidation() {
        std::vector<CleanRun> fit = {measuredPrescribed(2e-3, 2.0, 10.0, 4), measuredPrescribed(1e-3, 2.0, 10.0, 5)};
        const std::vector<CleanRun> original = fit;
        std::vector<CleanRun> val = {measuredPrescribed(3e-3, 2.0, 10.0, 6)};
        QVERIFY(holdOutLaterParts(fit, val, 0.6).empty());
        QCOMPARE(fit.size(), size_t(2));
        QCOMPARE(val.size(), size_t(3));
        for (size_t i = 0; i < 2; ++i) {
            const auto [a, b] = splitByTime(original[i], 0.6);
            QCOMPARE(fit[i].begin, a.begin);
            QCOMPARE(fit[i].end, a.end);
            QCOMPARE(val[i + 1].begin, b.begin);
            QCOMPARE(val[i + 1].end, b.end);
            QCOMPARE(val[i + 1].run.file, original[i].run.file + "#later");
        }
        // A fraction outside (0, 1) is refused and nothing moves.
        std::vector<CleanRun> fit2 = original, val2;
        const std::string e = holdOutLaterParts(fit2, val2, 1.0);
        QVERIFY(e.find("(0, 1)") != std::string::npos);
        QCOMPARE(fit2.size(), size_t(2));
        QVERIFY(val2.empty());
    }

    void unknownParameterIsRefused() {
        const std::vector<CleanRun> runs = {measuredPrescribed(2e-3, 2.0, 10.0, 5)};
        DatasetFitSettings st;
        st.free = {"mu", "viscosity"};
        const DatasetFit f = fitDataset(runs, {}, st);
        QVERIFY(!f.ok);
        QVERIFY(f.message.find("viscosity") != std::string::npos);
    }

    // A real damper run: t_N = band tension, so μ is the force per unit tension (the band
    // amplifies it); the fitted μ·t_N must match the measured sliding force level.
    void realDamperRunFitsSensibly() {
        io::Dataset ds;
        io::DatasetError err;
        QVERIFY(io::loadDataset({std::string(STICKSLIP_SHARED_DIR) + "/data/real/friction-damper/1Hz_36lb_1in.csv"}, {}, ds, err));
        CleanRun c;
        std::string why;
        QVERIFY(preprocessRun(ds.runs[0], PreprocessSettings{}, c, &why));
        DatasetFitSettings st;
        st.law = LawKind::Coulomb;
        st.free = {"mu", "epsT"};
        st.multistarts = 1;
        const DatasetFit f = fitDataset({c}, {}, st);
        QVERIFY2(f.ok, f.message.c_str());
        double tN = 0;
        QVERIFY(c.run.setting("tN", tN));
        std::vector<double> absF;
        for (size_t i = c.begin; i < c.end; ++i) absF.push_back(std::abs(c.run[Signal::Friction][i]));
        std::sort(absF.begin(), absF.end());
        const double level = absF[absF.size() * 3 / 4];
        qInfo("mu t_N = %.1f N, 75th percentile |F| = %.1f N, NRMSE %.3f", f.fit.value("mu") * tN, level, f.fitNrmse);
        QVERIFY(std::abs(f.fit.value("mu") * tN - level) < 0.2 * level);
        QVERIFY(f.fitNrmse > 0.0 && f.fitNrmse < 0.5);
    }

    // A run's SimParams: its known settings (k, m, t_N, A, f, phase) over the defaults, then the
    // model's values, which win; C1 follows μ unless given or untied; ζ sets c = 2 ζ sqrt(k m)
    // from the run's k and the final m; an unknown name is refused, naming it.
    void runParamsTakesTheRunsSettingsThenTheModels() {
        CleanRun run;
        run.run.settings = {{"k", 1234.0}, {"m", 0.61}, {"tN", 9.5}, {"A", 3e-3}, {"f", 2.5}, {"phase", 0.4}};
        ModelSpec spec;
        spec.values = {{"mu", 0.31}, {"eta", 1.7}, {"Dc", 4e-5}};
        SimParams p;
        p.rig.damping_Ns_per_m = 99.0;  // stale content is replaced
        std::string why;
        QVERIFY2(runParams(run, spec, p, &why), why.c_str());
        QCOMPARE(p.rig.stiffness_N_per_m, 1234.0);
        QCOMPARE(p.rig.mass_kg, 0.61);
        QCOMPARE(p.rig.normalForce_N, 9.5);
        QCOMPARE(p.drive.amplitude_m, 3e-3);
        QCOMPARE(p.drive.frequency_Hz, 2.5);
        QCOMPARE(p.drive.phase_rad, 0.4);
        QCOMPARE(p.rig.damping_Ns_per_m, SimParams{}.rig.damping_Ns_per_m);  // neither c nor ζ: the default
        QVERIFY(p.law == LawKind::RateState);
        QCOMPARE(p.lawParams<RateStateParams>().mu, 0.31);
        QCOMPARE(p.lawParams<RateStateParams>().C1, 0.31);  // tied to μ
        QCOMPARE(p.lawParams<RateStateParams>().eta_s_per_m, 1.7);
        QCOMPARE(p.lawParams<RateStateParams>().Dc_m, 4e-5);
        QCOMPARE(p.lawParams<RateStateParams>().vc_mps, RateStateParams{}.vc_mps);
        // The model's m over the run's; ζ with the run's k and that m.
        spec.values["m"] = 0.7;
        spec.values["zeta"] = 0.01;
        QVERIFY2(runParams(run, spec, p, &why), why.c_str());
        QCOMPARE(p.rig.mass_kg, 0.7);
        QCOMPARE(p.rig.damping_Ns_per_m, 2 * 0.01 * std::sqrt(1234.0 * 0.7));
        // The run's recorded c.
        spec.values.erase("zeta");
        run.run.settings["c"] = 0.77;
        QVERIFY2(runParams(run, spec, p, &why), why.c_str());
        QCOMPARE(p.rig.damping_Ns_per_m, 0.77);
        // C1 given, or untied: not μ.
        spec.values["C1"] = 0.2;
        QVERIFY2(runParams(run, spec, p, &why), why.c_str());
        QCOMPARE(p.lawParams<RateStateParams>().C1, 0.2);
        spec.values.erase("C1");
        spec.tieC1ToMu = false;
        QVERIFY2(runParams(run, spec, p, &why), why.c_str());
        QCOMPARE(p.lawParams<RateStateParams>().C1, RateStateParams{}.C1);
        spec.law = LawKind::Coulomb;
        QVERIFY2(runParams(run, spec, p, &why), why.c_str());
        QVERIFY(p.law == LawKind::Coulomb);
        spec.values["viscosity"] = 1.0;
        QVERIFY(!runParams(run, spec, p, &why));
        QVERIFY2(why.find("'viscosity'") != std::string::npos, why.c_str());
    }

    // At the parameters that made a noise-free run (law steps as the data were made), the
    // prediction is the run's force: the law starts from the measured force at the start of the
    // warm-up and forgets α's start (0) within its slip of many D_c. It covers the fit window
    // every stride-th sample; predictRun (the dispatch through runParams, t_N from the run) gives
    // the same numbers; another μ does not reproduce the force.
    void predictPrescribedReproducesTheSimulatedForce() {
        const CleanRun c = measuredPrescribed(2e-3, 2.0, 10.0, 1, false, 0.0);
        double rms = 0;
        for (size_t i = c.begin; i < c.end; ++i) rms += c.run[Signal::Friction][i] * c.run[Signal::Friction][i];
        rms = std::sqrt(rms / double(c.end - c.begin));
        PredictSettings s;
        s.stride = 1;
        s.substeps = 8;
        const Prediction p = predictPrescribed(c, FrictionLaw{RateStateLaw{truthLaw()}}, 10.0, s);
        QVERIFY2(p.ok, p.message.c_str());
        QCOMPARE(p.index.size(), c.end - c.begin);
        QCOMPARE(p.index.front(), c.begin);
        QCOMPARE(p.index.back(), c.end - 1);
        QCOMPARE(p.force_N.size(), p.index.size());
        QVERIFY(p.slider_m.empty());
        const double worst = worstForceError(c, p);
        qInfo("largest force error at the true parameters: %.3g N (force RMS %.3g N)", worst, rms);
        QVERIFY(worst < 1e-6 * rms);
        const Prediction viaSpec = predictRun(c, SetupKind::Prescribed, truthSpec(), s);
        QVERIFY2(viaSpec.ok, viaSpec.message.c_str());
        QVERIFY(viaSpec.index == p.index);
        QVERIFY(viaSpec.force_N == p.force_N);
        // Decimated: every 4th sample of the window, still close to the force.
        s.stride = 4;
        s.substeps = 32;
        const Prediction d = predictPrescribed(c, FrictionLaw{RateStateLaw{truthLaw()}}, 10.0, s);
        QVERIFY2(d.ok, d.message.c_str());
        QVERIFY(d.index.front() >= c.begin && d.index.front() < c.begin + 4 && d.index.back() < c.end);
        for (size_t k = 1; k < d.index.size(); ++k) QCOMPARE(d.index[k] - d.index[k - 1], size_t(4));
        QVERIFY2(worstForceError(c, d) < 0.02 * rms, qPrintable(QString::number(worstForceError(c, d))));
        // Another law: the comparison sees it.
        RateStateParams other = truthLaw();
        other.mu = 0.44;
        s.stride = 1;
        s.substeps = 8;
        const Prediction o = predictPrescribed(c, FrictionLaw{RateStateLaw{other}}, 10.0, s);
        QVERIFY(o.ok && worstForceError(c, o) > 0.05 * rms);
        // No friction force: refused, naming the run.
        CleanRun noForce = c;
        noForce.run[Signal::Friction].clear();
        const Prediction n = predictPrescribed(noForce, FrictionLaw{RateStateLaw{truthLaw()}}, 10.0, s);
        QVERIFY(!n.ok);
        QVERIFY2(n.message.find(c.run.file) != std::string::npos, n.message.c_str());
    }

    // NRMSE = RMS(prediction − measured) / RMS(measured) over the scored samples. The prediction
    // does not read the measured force in the window (the law starts at the warm-up), so a run
    // whose scored force is the model's own prediction scores 0 exactly, and shifted by δ it
    // scores rms_N = |δ|, NRMSE = |δ| / RMS(prediction + δ). At the true law the error of a
    // noisy run is its 0.05 N noise. An unknown model name fails with NaN scores.
    void scoreRunIsTheNormalisedRmsOfThePredictionError() {
        const CleanRun c = measuredPrescribed(2e-3, 2.0, 10.0, 7);
        PredictSettings s;
        s.stride = 1;
        s.substeps = 8;
        Prediction p;
        const RunScore noisy = scoreRun(c, SetupKind::Prescribed, truthSpec(), s, "validation", &p);
        QVERIFY2(noisy.ok, noisy.message.c_str());
        QCOMPARE(noisy.file, c.run.file);
        QCOMPARE(noisy.role, std::string("validation"));
        QCOMPARE(noisy.samples, p.index.size());
        QCOMPARE(noisy.samples, c.end - c.begin);
        QCOMPARE(noisy.nrmse, noisy.nrmseForce);
        QCOMPARE(noisy.rms_m, 0.0);
        qInfo("force RMS error at the true law: %.4f N (noise 0.05 N)", noisy.rms_N);
        QVERIFY(std::abs(noisy.rms_N - 0.05) < 0.0025);
        CleanRun own = c;
        for (size_t k = 0; k < p.index.size(); ++k) own.run[Signal::Friction][p.index[k]] = p.force_N[k];
        const RunScore zero = scoreRun(own, SetupKind::Prescribed, truthSpec(), s, "fit");
        QVERIFY2(zero.ok, zero.message.c_str());
        QCOMPARE(zero.rms_N, 0.0);
        QCOMPARE(zero.nrmse, 0.0);
        const double delta = -0.3;
        double ms = 0;
        for (size_t k = 0; k < p.index.size(); ++k) {
            own.run[Signal::Friction][p.index[k]] += delta;
            ms += (p.force_N[k] + delta) * (p.force_N[k] + delta);
        }
        const RunScore shifted = scoreRun(own, SetupKind::Prescribed, truthSpec(), s, "fit");
        QVERIFY2(shifted.ok, shifted.message.c_str());
        QVERIFY(std::abs(shifted.rms_N - 0.3) < 1e-12);
        const double want = 0.3 / std::sqrt(ms / double(p.index.size()));
        QVERIFY2(std::abs(shifted.nrmse - want) < 1e-12 * want, qPrintable(QString("%1 vs %2").arg(shifted.nrmse).arg(want)));
        ModelSpec bad = truthSpec();
        bad.values["viscosity"] = 1.0;
        const RunScore failed = scoreRun(c, SetupKind::Prescribed, bad, s, "fit");
        QVERIFY(!failed.ok);
        QVERIFY(std::isnan(failed.nrmse));
        QVERIFY2(failed.message.find("viscosity") != std::string::npos, failed.message.c_str());
    }
};

// QTEST_GUILESS_MAIN with a longer per-function watchdog than Qt's default 300 s: these fits
// need ~20 s of CPU, which a loaded machine (or a sanitizer build) can stretch past 5 minutes.
int main(int argc, char** argv) {
    if (qEnvironmentVariableIsEmpty("QTEST_FUNCTION_TIMEOUT")) qputenv("QTEST_FUNCTION_TIMEOUT", "1800000");
    QCoreApplication app(argc, argv);
    TstFitPrescribed tc;
    QTEST_SET_MAIN_SOURCE_PATH
    return QTest::qExec(&tc, argc, argv);
}
#include "tst_fit_prescribed.moc"
