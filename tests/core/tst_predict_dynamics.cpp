// predictDynamics (multiple shooting in the dynamics set-up, issue 5): at the true parameters,
// on noise-free 1 kHz records of this project's own simulator, the prediction must reproduce the
// record. Two inputs of a segment are not measured and used to be guessed wrongly:
//  - the friction state α at a segment start: α is frozen while the slider sticks (no
//    healing), so the steady state at the measured V ≈ 0 (α = 0) is wrong there and the
//    predicted breakaway comes too late (on D05 the fit then lowered μ by 3 %);
//  - the stage between samples: linear interpolation makes u̇ jump at every sample, which
//    drives the stick mode sqrt((k + ε_T)/m*) through ε_T (on D05 m* +4 standard errors).
// Segments start where the slider slips (PredictSettings::slipStartFraction, default 0.5) and the
// stage is interpolated by cubic Hermite (Catmull–Rom) on the integration grid. The measured
// initial x, ẋ of a segment have errors of their own: fitInitialState (default on) profiles them out.
// The run's score (scoreRun) combines the force and slider channels.
#include <QtTest>

#include <cmath>

#include "core/identify/fit.hpp"
#include "core/identify/predict.hpp"
#include "core/integrate/simulate.hpp"

using namespace stickslip;
using namespace stickslip::identify;
using io::Signal;

namespace {

// A stick–slip run with C1 != μ (so that α matters at breakaway) and a stiff contact.
SimParams truth() {
    SimParams p;
    p.setup = SetupKind::Dynamics;
    p.law = LawKind::RateState;
    p.drive.amplitude_m = 2.5e-3;
    p.drive.frequency_Hz = 3.0;
    p.rig.normalForce_N = 6.2;
    p.rig.stiffness_N_per_m = 2000.0;
    p.rig.mass_kg = 0.52;
    p.rig.damping_Ns_per_m = dampingFromRatio(0.008, 2000.0, 0.52);
    p.lawParams<RateStateParams>().mu = 0.27;
    p.lawParams<RateStateParams>().C1 = 0.22;
    p.lawParams<RateStateParams>().eta_s_per_m = 0.8;
    p.lawParams<RateStateParams>().Dc_m = 25e-6;
    p.lawParams<RateStateParams>().vc_mps = 0.1;
    p.lawParams<RateStateParams>().epsT_N_per_m = 3e5;
    p.integration.dt_s = 1.0 / 100000.0;
    p.integration.outputInterval_s = 1e-3;
    p.cycles = 9;
    p.transientCycles = 3;
    return p;
}

struct Record {
    CleanRun run;
    double stuckFraction = 0.0;
};

// The record as a rig would give it at 1 kHz, without noise; no filters (nothing to remove).
Record record(const SimParams& p) {
    const RunResult r = simulateDynamics(p);
    if (!r.ok()) qFatal("%s", r.message.c_str());
    io::Run run;
    run.file = "noise-free";
    double stuck = 0;
    for (const Sample& s : r.samples) {
        run[Signal::Time].push_back(s.t_s);
        run[Signal::StageDisp].push_back(s.stage_m);
        run[Signal::SliderDisp].push_back(s.slider_m);
        run[Signal::Friction].push_back(s.force_N);
        stuck += s.stuck ? 1.0 : 0.0;
    }
    run.settings = {{"k", p.rig.stiffness_N_per_m}, {"m", p.rig.mass_kg}, {"c", p.rig.damping_Ns_per_m},
                    {"tN", p.rig.normalForce_N}, {"f", p.drive.frequency_Hz}};
    Record rec;
    PreprocessSettings pre;
    pre.filters.bandStop = false;
    pre.filters.lowPass = false;
    std::string why;
    if (!preprocessRun(run, pre, rec.run, &why)) qFatal("%s", why.c_str());
    rec.stuckFraction = stuck / static_cast<double>(r.samples.size());
    return rec;
}

ModelSpec specOf(const SimParams& p) {
    ModelSpec m;
    m.law = LawKind::RateState;
    m.tieC1ToMu = false;
    m.values = {{"mu", p.lawParams<RateStateParams>().mu}, {"C1", p.lawParams<RateStateParams>().C1}, {"eta", p.lawParams<RateStateParams>().eta_s_per_m},
                {"Dc", p.lawParams<RateStateParams>().Dc_m}, {"vc", p.lawParams<RateStateParams>().vc_mps}, {"epsT", p.lawParams<RateStateParams>().epsT_N_per_m}};
    return m;
}

// RMS of (prediction − record) over the predicted samples, relative to the record's RMS.
std::pair<double, double> nrmse(const CleanRun& c, const Prediction& pr) {
    double eF = 0, mF = 0, eX = 0, mX = 0;
    for (size_t k = 0; k < pr.index.size(); ++k) {
        const double F = c.run[Signal::Friction][pr.index[k]], x = c.run[Signal::SliderDisp][pr.index[k]];
        eF += (pr.force_N[k] - F) * (pr.force_N[k] - F);
        mF += F * F;
        eX += (pr.slider_m[k] - x) * (pr.slider_m[k] - x);
        mX += x * x;
    }
    return {std::sqrt(eF / mF), std::sqrt(eX / mX)};
}

}  // namespace

class TstPredictDynamics : public QObject {
    Q_OBJECT
private slots:
    void reproducesANoiseFreeRecordAtTheTrueParameters() {
        const SimParams p = truth();
        const Record rec = record(p);
        qInfo("stuck %.0f %% of the time", 100 * rec.stuckFraction);
        QVERIFY(rec.stuckFraction > 0.2 && rec.stuckFraction < 0.8);  // stick-slip, not permanent stick or sliding
        PredictSettings ps;
        ps.slipStartFraction = 0.5;
        ps.fitInitialState = false;  // the measured state is exact here
        const Prediction pr = predictRun(rec.run, SetupKind::Dynamics, specOf(p), ps);
        QVERIFY2(pr.ok, pr.message.c_str());
        QVERIFY(pr.index.size() >= 40);
        const auto [eF, eX] = nrmse(rec.run, pr);
        qInfo("NRMSE at the true parameters, segments starting in slip: force %.2e, slider %.2e (%zu points)", eF, eX,
              pr.index.size());
        QVERIFY2(eF < 5e-3, qPrintable(QString("force NRMSE %1").arg(eF)));
        QVERIFY2(eX < 5e-3, qPrintable(QString("slider NRMSE %1").arg(eX)));
        // Segments at the nominal times start while stuck too, with α = 0 instead
        // of its frozen end-of-slip value: the breakaway is mispredicted (measured 3.5e-2).
        ps.slipStartFraction = 0.0;
        const Prediction p0 = predictRun(rec.run, SetupKind::Dynamics, specOf(p), ps);
        QVERIFY2(p0.ok, p0.message.c_str());
        const auto [eF0, eX0] = nrmse(rec.run, p0);
        qInfo("NRMSE at the true parameters, segments at the nominal times: force %.2e, slider %.2e", eF0, eX0);
        QVERIFY(eF0 > 10 * eF);
    }

    // Every segment starts at a sample where |V| >= slipStartFraction · max |V|, unless none
    // lies within its spacing; segments do not overlap.
    void segmentsStartWhereTheSliderSlips() {
        const Record rec = record(truth());
        PredictSettings ps;
        ps.slipStartFraction = 0.5;
        const Prediction pr = predictRun(rec.run, SetupKind::Dynamics, specOf(truth()), ps);
        QVERIFY2(pr.ok, pr.message.c_str());
        const std::vector<double>& V = rec.run.run[Signal::RelVel];
        double vmax = 0;
        for (size_t i = rec.run.begin; i < rec.run.end; ++i) vmax = std::max(vmax, std::abs(V[i]));
        const size_t stride = static_cast<size_t>(ps.residualStride);
        int starts = 0, inSlip = 0;
        for (size_t k = 0; k < pr.index.size(); ++k) {
            if (k > 0) QVERIFY(pr.index[k] > pr.index[k - 1]);
            if (k > 0 && pr.index[k] - pr.index[k - 1] == stride) continue;
            const size_t s0 = pr.index[k] - stride;  // the first residual point is `stride` after the start
            ++starts;
            if (std::abs(V[s0]) >= 0.5 * vmax) ++inSlip;
        }
        qInfo("%d of %d segments start in slip", inSlip, starts);
        QVERIFY(starts >= 4);
        QCOMPARE(inSlip, starts);
    }

    // Errors in the measured initial state (here: the velocity column off by a slowly varying
    // 3 mm/s, the size of the Savitzky–Golay error on noisy 1 kHz records) persist through a
    // segment. With PredictSettings::fitInitialState each segment's (x0, ẋ0) is estimated from
    // the segment itself, and the prediction at the true parameters is back to the clean one.
    void initialStateFittedPerSegmentRemovesMeasuredStateErrors() {
        const SimParams p = truth();
        Record rec = record(p);
        std::vector<double>& v = rec.run.run[Signal::SliderVel];
        const std::vector<double>& t = rec.run.run[Signal::Time];
        for (size_t i = 0; i < v.size(); ++i) v[i] += 3e-3 * std::sin(2 * M_PI * 0.7 * t[i] + 0.3);
        PredictSettings ps;
        ps.slipStartFraction = 0.5;
        ps.fitInitialState = false;
        const Prediction measured = predictRun(rec.run, SetupKind::Dynamics, specOf(p), ps);
        QVERIFY2(measured.ok, measured.message.c_str());
        QCOMPARE(measured.nuisanceParameters, size_t(0));
        const auto [eFm, eXm] = nrmse(rec.run, measured);
        ps.fitInitialState = true;
        const Prediction fitted = predictRun(rec.run, SetupKind::Dynamics, specOf(p), ps);
        QVERIFY2(fitted.ok, fitted.message.c_str());
        const auto [eFf, eXf] = nrmse(rec.run, fitted);
        qInfo("NRMSE with the velocity error: measured initial state F %.2e x %.2e; fitted F %.2e x %.2e", eFm, eXm, eFf,
              eXf);
        QCOMPARE(fitted.index, measured.index);  // same residual layout
        size_t segments = 0;
        for (size_t k = 0; k < fitted.index.size(); ++k)
            if (k == 0 || fitted.index[k] - fitted.index[k - 1] != static_cast<size_t>(ps.residualStride)) ++segments;
        QCOMPARE(fitted.nuisanceParameters, 2 * segments);
        QVERIFY2(eXm > 2e-2, "the velocity error must matter for this check to mean anything");
        QVERIFY2(eXf < 5e-3 && eFf < 5e-3, qPrintable(QString("fitted: F %1, x %2").arg(eFf).arg(eXf)));
        ps.initialStateIterations = 0;
        QVERIFY(!ps.validate().empty());
    }

    // scoreRun in the dynamics set-up (fit.hpp): each channel's NRMSE over the predicted samples
    // (RMS error / RMS of the record there), combined as sqrt((NRMSE_F² + NRMSE_x²)/2), and the
    // slider's RMS error in metres; small at the true parameters, larger for another μ.
    void scoreRunCombinesForceAndSliderChannels() {
        const SimParams p = truth();
        const Record rec = record(p);
        PredictSettings ps;
        ps.fitInitialState = false;
        Prediction pr;
        const RunScore sc = scoreRun(rec.run, SetupKind::Dynamics, specOf(p), ps, "fit", &pr);
        QVERIFY2(sc.ok, sc.message.c_str());
        QCOMPARE(sc.role, std::string("fit"));
        QCOMPARE(sc.samples, pr.index.size());
        QCOMPARE(pr.slider_m.size(), pr.index.size());
        const auto [eF, eX] = nrmse(rec.run, pr);
        qInfo("scoreRun at the true parameters: force %.3e, slider %.3e, combined %.3e", sc.nrmseForce, sc.nrmseDisp, sc.nrmse);
        QVERIFY(eF > 0 && eX > 0);  // the relative comparisons below mean something
        QVERIFY(std::abs(sc.nrmseForce - eF) <= 1e-12 * eF);
        QVERIFY(std::abs(sc.nrmseDisp - eX) <= 1e-12 * eX);
        QVERIFY(std::abs(sc.nrmse - std::sqrt(0.5 * (eF * eF + eX * eX))) <= 1e-12 * sc.nrmse);
        double ex2 = 0;
        for (size_t k = 0; k < pr.index.size(); ++k)
            ex2 += std::pow(pr.slider_m[k] - rec.run.run[Signal::SliderDisp][pr.index[k]], 2);
        QVERIFY(std::abs(sc.rms_m - std::sqrt(ex2 / double(pr.index.size()))) <= 1e-12 * sc.rms_m);
        QVERIFY(sc.nrmse < 5e-3);
        ModelSpec other = specOf(p);
        other.values["mu"] = 0.32;
        const RunScore worse = scoreRun(rec.run, SetupKind::Dynamics, other, ps, "fit");
        QVERIFY2(worse.ok, worse.message.c_str());
        QVERIFY(worse.nrmse > 5 * sc.nrmse);
    }

    void rejectsABadSlipStartFraction() {
        PredictSettings ps;
        ps.slipStartFraction = 1.5;
        const ParamIssues bad = ps.validate();
        QCOMPARE(bad.size(), size_t(1));
        QVERIFY(bad.front().message().find("slip start fraction") != std::string::npos);
        QVERIFY(bad.front().message().find("[0, 1)") != std::string::npos);
        ps.slipStartFraction = 0.0;
        QVERIFY(ps.validate().empty());
    }
};

QTEST_GUILESS_MAIN(TstPredictDynamics)
#include "tst_predict_dynamics.moc"
