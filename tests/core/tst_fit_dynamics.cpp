// Dynamics set-up fit (multiple shooting) on runs made with this project's own simulator
// (no hidden effect), "measured" with sensor noise: the law parameters come back within the
// reported standard errors, and the fitted model beats a wrong (Coulomb) law on held-out data.
#include <QtTest>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <map>

#include "core/identify/fit.hpp"
#include "core/integrate/simulate.hpp"

using namespace stickslip;
using namespace stickslip::identify;
using io::Signal;

namespace {

SimParams truth(double A_m) {
    SimParams p;
    p.setup = SetupKind::Dynamics;
    p.law = LawKind::RateState;
    p.drive.amplitude_m = A_m;
    p.drive.frequency_Hz = 3.0;
    p.rig.normalForce_N = 6.2;
    p.rig.stiffness_N_per_m = 8446.0;
    p.rig.mass_kg = 0.53;
    p.rig.damping_Ns_per_m = dampingFromRatio(0.005, 8446.0, 0.53);
    p.lawParams<RateStateParams>().mu = 0.25;
    p.lawParams<RateStateParams>().C1 = 0.25;
    p.lawParams<RateStateParams>().eta_s_per_m = 0.6;
    p.lawParams<RateStateParams>().Dc_m = 20e-6;
    p.lawParams<RateStateParams>().vc_mps = 0.1;
    p.lawParams<RateStateParams>().epsT_N_per_m = 1e5;
    p.integration.dt_s = 1.0 / 30000.0;
    p.integration.outputInterval_s = 1e-3;
    p.cycles = 12;
    p.transientCycles = 3;
    return p;
}

// A run as the rig would record it: 1 kHz, 10 µm displacement noise, 0.05 N force noise.
CleanRun measured(const SimParams& p, uint64_t seed) {
    const RunResult r = simulateDynamics(p);
    io::Run run;
    run.file = "synthetic_A" + std::to_string(p.drive.amplitude_m * 1e3) + "mm";
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> dn(0.0, 10e-6), fn(0.0, 0.05);
    for (const Sample& s : r.samples) {
        run[Signal::Time].push_back(s.t_s);
        run[Signal::StageDisp].push_back(s.stage_m + dn(rng));
        run[Signal::SliderDisp].push_back(s.slider_m + dn(rng));
        run[Signal::Friction].push_back(s.force_N + fn(rng));
    }
    run.settings = {{"k", p.rig.stiffness_N_per_m}, {"m", p.rig.mass_kg}, {"c", p.rig.damping_Ns_per_m},
                    {"tN", p.rig.normalForce_N}, {"f", p.drive.frequency_Hz}};
    CleanRun c;
    std::string why;
    PreprocessSettings pre;
    // White noise, no mains: filters off, so that the test checks the fit and its standard
    // errors. (With the default 100 Hz low-pass on, the smoothed stick-slip corners bias the
    // fit: measured μ = 0.2368 ± 0.0018 and η = 1.10 ± 0.19 for the true 0.25 and 0.6.) The stage
    // input is still the Fourier fit of the noisy stage record (the default).
    pre.filters.bandStop = false;
    pre.filters.lowPass = false;
    if (!preprocessRun(run, pre, c, &why)) qFatal("%s", why.c_str());
    return c;
}

// The runs of a dataset through the default preprocessing (which must filter them).
std::vector<CleanRun> cleanDefault(const io::Dataset& ds) {
    std::vector<CleanRun> out;
    for (const io::Run& r : ds.runs) {
        CleanRun c;
        std::string why;
        if (!preprocessRun(r, PreprocessSettings{}, c, &why)) qFatal("%s", why.c_str());
        if (c.filter.empty()) qFatal("default preprocessing should filter the signals");
        out.push_back(std::move(c));
    }
    return out;
}

// One fitted parameter against the answer key: z = (fitted - true)/stderr, and whether it ended
// on one of its bounds (then not asserted).
struct AnswerCheck {
    std::string name;
    double z;
    bool atBound;
    double se;
};

// Every free parameter of `f` against the answer key's baseline_params, each printed with its
// three standard errors (reported, iid, jackknife).
std::vector<AnswerCheck> compareWithAnswerKey(const DatasetFit& f, const std::vector<std::string>& free, const nlohmann::json& key) {
    std::vector<AnswerCheck> checks;
    for (const std::string& name : free) {
        const double truth = key["baseline_params"][name].get<double>();
        const double got = f.fit.value(name), se = f.fit.stderrOf(name);
        FitParameter fp{"zeta", 0.005, 1e-5, 1.0, true, ParamScale::Log};  // fitDataset's zeta bounds
        if (name != "zeta" && !defaultParameter(name, SetupKind::Dynamics, fp)) qFatal("no default for %s", name.c_str());
        const bool atBound = std::abs(got - fp.lower) < 1e-6 * (fp.upper - fp.lower) ||
                             std::abs(fp.upper - got) < 1e-6 * (fp.upper - fp.lower);
        double seIid = NAN, seJk = NAN;
        for (size_t i = 0; i < f.fit.names.size(); ++i)
            if (f.fit.names[i] == name) {
                if (i < f.stderrsIid.size()) seIid = f.stderrsIid[i];
                if (i < f.stderrsJackknife.size()) seJk = f.stderrsJackknife[i];
            }
        qInfo("%-5s = %.5g +- %.3g (iid %.3g, jackknife %.3g), answer key %.5g: %.2f stderr%s", name.c_str(), got, se, seIid,
              seJk, truth, (got - truth) / se, atBound ? " (at a bound: not asserted)" : "");
        checks.push_back({name, (got - truth) / se, atBound, se});
    }
    return checks;
}

}  // namespace

class TstFitDynamics : public QObject {
    Q_OBJECT
private slots:
    void recoversLawParametersWithinStandardErrors() {
        std::vector<CleanRun> runs = {measured(truth(1.0e-3), 1), measured(truth(2.0e-3), 2)};
        std::vector<CleanRun> held = {measured(truth(1.5e-3), 3)};
        DatasetFitSettings st;
        st.setup = SetupKind::Dynamics;
        st.law = LawKind::RateState;
        st.free = {"mu", "eta", "vc"};
        st.start = {{"Dc", 20e-6}, {"epsT", 1e5}, {"mu", 0.2}, {"eta", 1.0}, {"vc", 0.05}};
        st.estimateStart = false;
        st.predict.dt_s = 1.0 / 30000.0;
        st.predict.segment_s = 0.05;
        st.predict.segmentSpacing_s = 0.2;
        st.multistarts = 2;
        const DatasetFit f = fitDataset(runs, held, st);
        QVERIFY2(f.ok, f.message.c_str());
        qInfo("%s", f.fit.solverSummary.c_str());
        qInfo("%s", f.fit.identifiabilityMessage.c_str());
        const std::map<std::string, double> want = {{"mu", 0.25}, {"eta", 0.6}, {"vc", 0.1}};
        QVERIFY(f.fit.identifiable);
        for (const auto& [name, v] : want) {
            const double got = f.fit.value(name), se = f.fit.stderrOf(name);
            qInfo("%s = %.5g +- %.3g (true %.5g)", name.c_str(), got, se, v);
            QVERIFY(se > 0);
            QVERIFY2(std::abs(got - v) < 4 * se, qPrintable(QString::fromStdString(name)));
        }
        qInfo("fit NRMSE %.4f, validation NRMSE %.4f", f.fitNrmse, f.validationNrmse);
        QVERIFY(f.validationNrmse < 0.2);
        // A Coulomb law fitted to the same runs predicts the held-out run worse.
        DatasetFitSettings sc = st;
        sc.law = LawKind::Coulomb;
        sc.free = {"mu"};
        const DatasetFit c = fitDataset(runs, held, sc);
        QVERIFY2(c.ok, c.message.c_str());
        qInfo("Coulomb: fit NRMSE %.4f, validation NRMSE %.4f", c.fitNrmse, c.validationNrmse);
        QVERIFY(c.validationNrmse > f.validationNrmse);
    }

    // DatasetFitSettings::curveCoordinates changes the solver's coordinates only: with C1, eta
    // and vc free, a fit in (kappa = C1/vc^2, s = eta - C1/vc, vc) started at the optimum of the
    // fit in (C1, eta, vc) stays there, and reports the same values, standard errors (delta
    // method) and correlations. (From the same distant start the two may end in different
    // minima: measured plain 0.8658, curve 0.8663, chi2 0.34 apart but mu 1.1 stderr apart; the
    // cost is not quadratic at that scale.) The standard errors agree only to a factor 1.5: the
    // problem is ill-conditioned along the C1-eta-vc valley, where the numeric Jacobian's small
    // errors decide (JtJ)^-1 (measured at the same optimum with difference step 1e-5: mu
    // 0.00119 plain vs 0.00084 curve, vc 0.0152 vs 0.0113; with 1e-4: mu -24 %, C1 +26 %, eta
    // +27 %; correlations differ by up to 0.88, mu-vc -0.43 plain vs +0.45 curve, the curve one
    // matching the valley, in which C1, eta, vc rise together). The numeric Jacobian depends on
    // its step here (with the same coordinates, steps 1e-4 and 1e-5 give stderrs 20-30 % apart):
    // probably because the residuals are only piecewise smooth (a stick-slip transition that
    // moves across a time step boundary makes a kink; not verified). Hence no assertion on correlations; the map and the delta method themselves
    // are checked exactly in tst_fit_engine.
    void curveCoordinatesChangeOnlyTheSolverCoordinates() {
        std::vector<CleanRun> runs = {measured(truth(1.0e-3), 11), measured(truth(2.0e-3), 12)};
        DatasetFitSettings st;
        st.setup = SetupKind::Dynamics;
        st.law = LawKind::RateState;
        st.free = {"mu", "C1", "eta", "vc"};
        st.start = {{"Dc", 20e-6}, {"epsT", 1e5}, {"mu", 0.24}, {"C1", 0.3}, {"eta", 0.7}, {"vc", 0.12}};
        st.estimateStart = false;
        st.autoScan = false;
        st.predict.dt_s = 1.0 / 30000.0;
        st.predict.segment_s = 0.05;
        st.predict.segmentSpacing_s = 0.2;
        st.multistarts = 1;
        st.maxIterations = 100;
        st.curveCoordinates = false;
        const DatasetFit plain = fitDataset(runs, {}, st);
        QVERIFY2(plain.ok, plain.message.c_str());
        qInfo("plain: %s", plain.fit.solverSummary.c_str());
        QVERIFY(plain.fit.converged);
        QVERIFY(plain.fit.solverSummary.find("steady-state curve") == std::string::npos);
        for (const std::string& n : st.free) st.start[n] = plain.fit.value(n);
        st.curveCoordinates = true;
        const DatasetFit curve = fitDataset(runs, {}, st);
        QVERIFY2(curve.ok, curve.message.c_str());
        qInfo("curve: %s", curve.fit.solverSummary.c_str());
        QVERIFY(curve.fit.solverSummary.find("steady-state curve") != std::string::npos);
        QCOMPARE(curve.fit.names, plain.fit.names);
        QCOMPARE(curve.fit.freeNames, plain.fit.freeNames);
        const double sigma2 = 2.0 * plain.fit.cost / static_cast<double>(plain.fit.residualCount);
        const double chi2 = 2.0 * (plain.fit.cost - curve.fit.cost) / sigma2;
        qInfo("cost plain %.8g, curve from there %.8g: chi2 lower by %.3g", plain.fit.cost, curve.fit.cost, chi2);
        for (const std::string& n : st.free)
            qInfo("%-4s plain %.6g +- %.3g, curve %.6g +- %.3g", n.c_str(), plain.fit.value(n), plain.fit.stderrOf(n),
                  curve.fit.value(n), curve.fit.stderrOf(n));
        // Not worse, and at most a small step further down (the plain solver stops by its function
        // tolerance; measured: curve 0.016 lower in chi2).
        QVERIFY(chi2 > -0.01 && chi2 < 0.1);
        // The standard errors are compared at one point, the curve fit's optimum, refitted in C1,
        // eta, vc from there: where the plain solver stops along the valley floor its differenced
        // standard errors move (mu: 0.00101 and 0.00126 at two stopping points 0.03 s.e. apart,
        // reached by two versions of the solver's line search). At one point they still differ by
        // up to 1.44x (mu: 0.00111 against the curve fit's 0.00077): the Jacobian differenced
        // through a simulated stick-slip run is not smooth at the solver's step, in either
        // coordinates.
        for (const std::string& n : st.free) st.start[n] = curve.fit.value(n);
        st.curveCoordinates = false;
        const DatasetFit there = fitDataset(runs, {}, st);
        QVERIFY2(there.ok, there.message.c_str());
        for (const std::string& n : st.free) {
            const double a = plain.fit.value(n), b = curve.fit.value(n);
            const double sa = there.fit.stderrOf(n), sb = curve.fit.stderrOf(n);
            qInfo("%-4s plain from the curve fit's optimum %.6g +- %.3g", n.c_str(), there.fit.value(n), sa);
            QVERIFY(sa > 0 && sb > 0);
            QVERIFY2(std::abs(a - b) < 0.3 * plain.fit.stderrOf(n), n.c_str());
            QVERIFY2(std::abs(std::log(sb / sa)) < std::log(1.5), n.c_str());
        }
        QCOMPARE(curve.fit.correlation.size(), plain.fit.correlation.size());
        // Without the jackknife the C1-eta-vc errors are flagged as too small (curve coordinates
        // active); with C1, eta, vc not all free there is no such flag.
        QVERIFY(curve.stderrWarning.find("jackknife") != std::string::npos);
        QVERIFY(plain.stderrWarning.empty());
    }

    // The independent simulator's D05 runs (answer key: no hidden effect), cleaned with the
    // default filters (the prediction passes through the same filter), fitted in the dynamics
    // set-up with every law parameter and the rig's m* and damping ratio free, with the defaults
    // of a user's fit: segments start in slip and their initial x, x' are profiled out
    // (PredictSettings), mu, C1, eta, vc and m* start from the equation-error fit and epsT from a
    // scan (DatasetFitSettings), and the standard errors are the larger of Jacobian x
    // sqrt(tau_int) and the jackknife over the 4 fit runs. Every free parameter must lie within
    // kFactor = 3 reported standard errors of the answer key, which is read only to check.
    // What it took so far (docs/fit-results.md, measured):
    //  - the measured initial state of a segment has errors (filtered x noise, the Savitzky-Golay
    //    velocity, stick ringing above the low-pass) that bias epsT, m* and zeta by 2-8 stderr:
    //    profiled out now;
    //  - segments that start in stick get a wrong friction state alpha (mu -3 %): they start in
    //    slip now;
    //  - the cost has narrow valleys in epsT (the stick ringing's frequency): from epsT = 1e6 every
    //    fit ended at 9e5-1e6 with cost 3.6-4.7, the key's valley has cost 0.97: the scan finds it;
    //  - the C1-eta-vc valley is curved: the solver works in the steady-state curve's slope,
    //    curvature and vc (DatasetFitSettings::curveCoordinates; 22-31 iterations instead of 40+
    //    without convergence), vc scanned first;
    //  - the cost has several minima along that valley (measured 1.0096-1.0140 from different
    //    starts, at C1 0.26-0.75), 5-15 Jacobian stderrs apart; the jackknife repeats the whole
    //    procedure on each 3-run subset, so its spread includes which minimum a fit finds.
    // The reported errors must also say something: relative stderr below kMaxRelative for the
    // parameters the data do determine (mu, epsT, m*: < 2 %, zeta < 25 %, Dc < 100 %); C1, eta
    // and vc individually are not determined (only the curve's slope and curvature are).
    void recoversD05AnswerKeyWithinStandardErrors() {
        constexpr double kFactor = 3.0;
        const std::map<std::string, double> kMaxRelative = {{"mu", 0.02}, {"epsT", 0.02}, {"m", 0.02}, {"zeta", 0.25}, {"Dc", 1.0}};
        const std::string dir = std::string(STICKSLIP_SHARED_DIR) + "/data/synthetic/";
        io::DatasetOptions opt;
        opt.manifestPath = dir + "D05/manifest.json";
        io::Dataset fitData, valData;
        io::DatasetError err;
        QVERIFY2(io::loadDataset({dir + "D05/run_01.csv", dir + "D05/run_02.csv", dir + "D05/run_03.csv", dir + "D05/run_04.csv"},
                                 opt, fitData, err), err.what().c_str());
        QVERIFY2(io::loadDataset({dir + "D05/run_05.csv"}, opt, valData, err), err.what().c_str());
        const std::vector<CleanRun> runs = cleanDefault(fitData), held = cleanDefault(valData);
        DatasetFitSettings st;
        st.setup = SetupKind::Dynamics;
        st.law = LawKind::RateState;
        st.free = {"mu", "C1", "eta", "Dc", "vc", "epsT", "m", "zeta"};
        st.multistarts = 1;
        st.jackknife = true;
        const DatasetFit f = fitDataset(runs, held, st);
        QVERIFY2(f.ok, f.message.c_str());
        qInfo("%s", f.fit.solverSummary.c_str());
        qInfo("%s; tau_int = %.2f; fit NRMSE %.4f, validation NRMSE %.4f", f.fit.identifiabilityMessage.c_str(), f.tauInt,
              f.fitNrmse, f.validationNrmse);
        QVERIFY(f.tauInt >= 1.0);
        QVERIFY(f.fitNrmse < 0.1);
        QVERIFY(f.validationNrmse < 0.1);
        QVERIFY2(f.fit.identifiable, f.fit.identifiabilityMessage.c_str());

        std::ifstream in(dir + "answers/D05.json");
        QVERIFY(in.good());
        const nlohmann::json key = nlohmann::json::parse(in);
        QCOMPARE(key["effect"].get<std::string>(), std::string("none"));
        // Measured with this code (2026-11-22, CLI, same settings): cost 1.0138 after 24
        // iterations (CONVERGENCE), fit / validation NRMSE 0.0178 / 0.0166; z (reported stderr,
        // the jackknife for all eight): mu -0.53, C1 +0.20, eta +0.35, Dc -0.99, vc +0.37,
        // epsT +0.62, m +0.10, zeta +1.14; relative stderr mu 0.8 %, epsT 0.7 %, m 0.5 %,
        // zeta 11 %, Dc 51 %.
        // Print every parameter first, then assert (a failure must not hide the others).
        const std::vector<AnswerCheck> checks = compareWithAnswerKey(f, st.free, key);
        int asserted = 0;
        for (const AnswerCheck& c : checks) {
            if (c.atBound) continue;
            QVERIFY(std::isfinite(c.se) && c.se > 0);
            QVERIFY2(std::abs(c.z) <= kFactor, c.name.c_str());
            const auto cap = kMaxRelative.find(c.name);
            if (cap != kMaxRelative.end())
                QVERIFY2(c.se <= cap->second * std::abs(f.fit.value(c.name)), qPrintable(QString::fromStdString(c.name + ": stderr too large to say anything")));
            ++asserted;
        }
        QCOMPARE(asserted, 8);
        QCOMPARE(f.jackknifeFits, 4);
        QVERIFY(f.stderrWarning.empty());
    }
};

// QTEST_GUILESS_MAIN with a longer per-function watchdog than Qt's default 300 s: these fits
// need ~20 s of CPU, which a loaded machine (or a sanitizer build) can stretch past 5 minutes.
int main(int argc, char** argv) {
    if (qEnvironmentVariableIsEmpty("QTEST_FUNCTION_TIMEOUT")) qputenv("QTEST_FUNCTION_TIMEOUT", "1800000");
    QCoreApplication app(argc, argv);
    TstFitDynamics tc;
    QTEST_SET_MAIN_SOURCE_PATH
    return QTest::qExec(&tc, argc, argv);
}
#include "tst_fit_dynamics.moc"
