// Selection tests of the identify loop (identify_selection.cpp) on hand-made error tables, the
// warm-start clamp of the fit parameters (identify_fit.cpp), and the law run that Jacobian
// columns of rig and sensor parameters share (identify_residuals.cpp), and the state a measured
// run starts the law from.
#include <QtTest/QtTest>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "core/identify/effects/registry.hpp"

#include "core/identify/identify_internal.hpp"

using namespace stickslip;
using namespace stickslip::identify;
using namespace stickslip::identify::detail;

namespace {

ModelErrors errors(const std::vector<double>& heldOut) {
    ModelErrors e;
    double ss = 0;
    for (double v : heldOut) {
        RunError r;
        r.heldOutNrmse = v;
        e.runs.push_back(r);
        ss += v * v;
    }
    e.validationNrmse = std::sqrt(ss / static_cast<double>(heldOut.size()));
    return e;
}

// The selection of one candidate of five held-out runs under the default options.
bool select(CandidateScore& sc, const ModelErrors& ref, const ModelErrors& with) {
    static const IdentifyOptions opt;
    Context cx;
    cx.opt = &opt;
    return passesSelection(cx, sc, FitOutcome{}, ref, with, {}, {0, 1, 2, 3, 4}, 1.0);
}

// A stick–slip-like run (3 Hz, 2 s at 1 kHz) in either set-up.
IdentifyRun syntheticRun(SetupKind setup) {
    IdentifyRun r;
    r.setup = setup;
    r.normalForce_N = 6.2;
    r.stiffness_N_per_m = 3000;
    const double w = 2 * M_PI * 3;
    for (int i = 0; i < 2000; ++i) {
        const double t = i * 1e-3;
        r.t_s.push_back(t);
        r.slip_m.push_back(1e-3 * std::sin(w * t));
        r.relVel_mps.push_back(1e-3 * w * std::cos(w * t));
        r.accel_mps2.push_back(-1e-3 * w * w * std::sin(w * t));
        r.force_N.push_back(1.6 * std::tanh(2e3 * r.relVel_mps.back()) + 0.01 * std::sin(37.0 * t));
        r.slider_m.push_back(2e-4 * std::sin(w * t + 0.3));
        r.sliderVel_mps.push_back(2e-4 * w * std::cos(w * t + 0.3));
    }
    return r;
}

Prepared prepared(const IdentifyRun& r) {
    Prepared p;
    p.run = &r;
    p.t = r.t_s;
    p.g = r.slip_m;
    p.V = r.relVel_mps;
    p.F = r.force_N;
    p.a = r.accel_mps2;
    p.x = r.slider_m;
    p.xd = r.sliderVel_mps;
    if (r.setup == SetupKind::Dynamics) prepareLawMasks(IdentifyOptions{}.stickVelocity_mps, p);
    return p;
}

}  // namespace

class TestIdentifySelection : public QObject {
    Q_OBJECT
private slots:
    // The law channel's masks: slides where |V| >= vStick; compared = slides less every sample
    // within edgeGuard of one that does not slide (IdentifyOptions::maskEdgeGuard).
    void lawMasksErodeTheSlidingSetByTheEdgeGuard() {
        Prepared p;
        p.t = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
        p.V = {0, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0, 0.1, 0.1};
        prepareLawMasks(0.005, p);
        QCOMPARE(p.slides, (std::vector<char>{0, 1, 1, 1, 1, 1, 1, 0, 1, 1}));
        QCOMPARE(p.compared, p.slides);  // no guard: every sliding sample
        p.edgeGuard = 2;
        prepareLawMasks(0.005, p);
        QCOMPARE(p.slides, (std::vector<char>{0, 1, 1, 1, 1, 1, 1, 0, 1, 1}));
        QCOMPARE(p.compared, (std::vector<char>{0, 0, 0, 1, 1, 0, 0, 0, 0, 0}));
    }

    // Prepared::filtered with the model's force where the mask is off (stickRigPrediction): an
    // exact model's prediction is the cleaned measurement on every sample, edges included. The
    // anchored form F + filter(mask·(y − F)) is not: it adds F − filter(F) where F bends fast.
    void filteredWholeModelIsTheCleanedMeasurementForAnExactModel() {
        Prepared p;
        const size_t n = 400;
        std::vector<double> raw(n);
        p.slides.assign(n, 0);
        for (size_t i = 0; i < n; ++i) {
            const double t = static_cast<double>(i) / 500.0;
            p.slides[i] = (i / 50) % 2;  // stick and slip in turns, each 0.1 s
            raw[i] = p.slides[i] ? 1.0 + 0.3 * std::sin(40.0 * t) : 0.2 * std::sin(6.0 * t);  // force jumps at each edge
        }
        p.predictionFilter = dsp::butterworthLowpass(4, 100.0, 500.0);
        p.F = dsp::filtfiltZeroExtended(p.predictionFilter, raw);  // the cleaned measurement
        const std::vector<double> whole = p.filtered(raw, p.slides, raw);
        double worstWhole = 0, worstAnchored = 0;
        const std::vector<double> anchored = p.filtered(raw, &p.slides);
        for (size_t i = 0; i < n; ++i) {
            worstWhole = std::max(worstWhole, std::abs(whole[i] - p.F[i]));
            if (p.slides[i]) worstAnchored = std::max(worstAnchored, std::abs(anchored[i] - p.F[i]));
        }
        qInfo("largest |prediction − F|: whole model %.2e, anchored %.2e", worstWhole, worstAnchored);
        QVERIFY2(worstWhole < 1e-12, qPrintable(QString::number(worstWhole)));
        QVERIFY2(worstAnchored > 1e-3, qPrintable(QString::number(worstAnchored)));  // next to the edges
        p.predictionFilter.clear();  // no cleaning: the prediction is the model's force itself
        QCOMPARE(p.filtered(raw, p.slides, std::vector<double>(n, 7.0)), raw);
    }

    // D16 (session 6): every leave-one-run-out refit of a candidate failed, its held-out error
    // was NaN, and the NaN slipped past the held-out comparison: the candidate was added.
    void noHeldOutErrorIsNoEvidence() {
        CandidateScore sc;
        sc.name = "stick_healing";
        const ModelErrors ref = errors({0.1, 0.1, 0.1, 0.1, 0.1});
        ModelErrors with = errors({0.05, 0.05, 0.05, 0.05, 0.05});
        with.validationNrmse = std::numeric_limits<double>::quiet_NaN();
        for (RunError& r : with.runs) r.heldOutNrmse = 0.0;
        QVERIFY(!select(sc, ref, with));
        QVERIFY2(sc.reason.find("no held-out error") != std::string::npos, sc.reason.c_str());
    }

    // Leave-one-run-out refits that all end at one value (stalled where they started, session 34:
    // a backlash's refits on active bounds) give a jackknife standard error of 0. That is not
    // evidence of a size: the size test takes the larger of the jackknife and the Jacobian
    // (× sqrt(τ_int)) standard errors, as fit's stderr does, and fails here; with the jackknife
    // alone it passed.
    void aJackknifeOfZeroIsNotEvidenceOfSize() {
        static const IdentifyOptions opt;
        Context cx;
        cx.opt = &opt;
        const ModelErrors ref = errors({0.10, 0.11, 0.12, 0.10, 0.13});
        const ModelErrors with = errors({0.05, 0.06, 0.05, 0.07, 0.05});
        FitOutcome fit;
        fit.values["backlash.halfWidth_m"] = 2e-6;
        fit.estimates.push_back({"backlash.halfWidth_m", 2e-6, 1e-6});  // Jacobian s.e.
        const std::vector<std::map<std::string, double>> stalled(5, {{"backlash.halfWidth_m", 2e-6}});
        CandidateScore sc;
        sc.name = "backlash";
        QVERIFY(!passesSelection(cx, sc, fit, ref, with, stalled, {0, 1, 2, 3, 4}, 4.0));
        QCOMPARE(sc.sizeStderr, 2e-6);  // 1e-6 × sqrt(4)
        QVERIFY2(sc.reason.find("is not identified") != std::string::npos, sc.reason.c_str());
        QVERIFY2(sc.sizeStderrKind.find("Jacobian") != std::string::npos, sc.sizeStderrKind.c_str());
        // Refits that spread: the jackknife is the larger and decides (it passes).
        const std::vector<std::map<std::string, double>> spread = {{{"backlash.halfWidth_m", 1.9e-6}},
                                                                   {{"backlash.halfWidth_m", 2.1e-6}},
                                                                   {{"backlash.halfWidth_m", 2.0e-6}},
                                                                   {{"backlash.halfWidth_m", 1.95e-6}},
                                                                   {{"backlash.halfWidth_m", 2.05e-6}}};
        fit.estimates.front().stderr_ = 1e-9;
        CandidateScore sc2;
        sc2.name = "backlash";
        QVERIFY2(passesSelection(cx, sc2, fit, ref, with, spread, {0, 1, 2, 3, 4}, 4.0), sc2.reason.c_str());
        QVERIFY2(sc2.sizeStderrKind.find("jackknife") != std::string::npos, sc2.sizeStderrKind.c_str());
        QVERIFY(sc2.sizeStderr > 1e-8);
    }

    // A candidate's point as a point of the model without it (withoutEffect): its parameters
    // go; viscous_damping's ζ continues the rig's ζ and is handed back, clamped to the rig's
    // baseline range. Inside that range the candidate is the baseline itself (stickslip-cli
    // synthesize --seed 1: a "viscous_damping" at ζ = 0.0055 was added on a set without an effect).
    void withoutEffectHandsContinuedParameterBack() {
        IdentifyOptions opt;
        Context cx;
        cx.opt = &opt;
        cx.anyDynamics = true;
        const Spec base;
        const std::map<std::string, double> inRange = {{"mu", 0.25}, {"m", 0.52}, {"viscous_damping.zeta", 0.0055}};
        std::map<std::string, double> v = withoutEffect(cx, base, "viscous_damping", inRange);
        QVERIFY(!v.count("viscous_damping.zeta"));
        QCOMPARE(v.at("zeta"), 0.0055);
        QCOMPARE(v.at("mu"), 0.25);
        v = withoutEffect(cx, base, "viscous_damping", {{"mu", 0.25}, {"viscous_damping.zeta", 0.1}});
        QCOMPARE(v.at("zeta"), ViscousDamping::kBaselineMax);
        // An effect that continues nothing only loses its parameters.
        v = withoutEffect(cx, base, "backlash", {{"mu", 0.25}, {"zeta", 0.006}, {"backlash.halfWidth_m", 5e-7}});
        QCOMPARE(v.size(), size_t(2));
        QCOMPARE(v.at("zeta"), 0.006);
        // Prescribed set-up: no rig ζ to hand back to.
        cx.anyDynamics = false;
        v = withoutEffect(cx, base, "viscous_damping", inRange);
        QVERIFY(!v.count("zeta") && !v.count("viscous_damping.zeta"));
    }

    // Five runs that all improve by very different amounts (D03's lag): the exact sign-flip
    // test decides (plain p = 1/32, mid-p 1/64), and the pooled and paired held-out tests pass.
    void heterogeneousGainsPassTheExactTest() {
        CandidateScore sc;
        sc.name = "frictional_lag";
        const ModelErrors ref = errors({0.10, 0.10, 0.10, 0.10, 0.10});
        const ModelErrors with = errors({0.10 * std::exp(-0.39 / 2), 0.10 * std::exp(-0.11 / 2), 0.10 * std::exp(-0.08 / 2),
                                         0.10 * std::exp(-1.39 / 2), 0.10 * std::exp(-0.08 / 2)});
        select(sc, ref, with);
        QVERIFY(sc.heldOutExact);
        QVERIFY(sc.heldOutMidP);
        QVERIFY2(std::abs(sc.heldOutP - 1.0 / 64.0) < 1e-12, qPrintable(QString::number(sc.heldOutP)));
        QCOMPARE(sc.heldOutExactP, 1.0 / 32.0);
        QCOMPARE(sc.heldOutUnits, 5);
        // One of the five worse by more than any other run gained: not consistent. Of the 32 sign
        // patterns five have a larger sum (all better; one of the four better runs flipped) and
        // one ties (the observed): plain p 6/32, mid-p 5.5/32.
        CandidateScore sc2;
        sc2.name = "frictional_lag";
        const ModelErrors mixed = errors({0.09, 0.09, 0.09, 0.09, 0.115});
        QVERIFY(!select(sc2, ref, mixed));
        QVERIFY2(std::abs(sc2.heldOutP - 5.5 / 32.0) < 1e-12, qPrintable(QString::number(sc2.heldOutP)));
        QVERIFY2(sc2.reason.find("mid-p") != std::string::npos, sc2.reason.c_str());
    }

    // One of five runs worse by the smallest change of the five (N301's lag, session 47: log MSE
    // ratios 0.150, 0.037, −0.022, 0.213, 0.186): the plain exact p is 2/32, above 5 %, so the plain
    // test demands all five runs better; its mid-p, 1.5/32, passes. The option keeps the plain one.
    void oneRunWorseByTheSmallestChangePassesByItsMidP() {
        const std::vector<double> d = {0.150, 0.037, -0.022, 0.213, 0.186};
        std::vector<double> w;
        for (double x : d) w.push_back(0.10 * std::exp(-x / 2));
        const ModelErrors ref = errors({0.10, 0.10, 0.10, 0.10, 0.10}), with = errors(w);
        CandidateScore mid;
        mid.name = "frictional_lag";
        QVERIFY2(select(mid, ref, with), mid.reason.c_str());
        QVERIFY2(std::abs(mid.heldOutP - 1.5 / 32.0) < 1e-12, qPrintable(QString::number(mid.heldOutP)));
        QCOMPARE(mid.heldOutExactP, 2.0 / 32.0);
        IdentifyOptions plain;
        plain.heldOutMidP = false;
        Context cx;
        cx.opt = &plain;
        CandidateScore sc;
        sc.name = "frictional_lag";
        QVERIFY(!passesSelection(cx, sc, FitOutcome{}, ref, with, {}, {0, 1, 2, 3, 4}, 1.0));
        QCOMPARE(sc.heldOutP, 2.0 / 32.0);
        QVERIFY(!sc.heldOutMidP);
        QVERIFY2(sc.reason.find("exact sign-flip test, one-sided p = 0.0625") != std::string::npos, sc.reason.c_str());
    }

    // Four held-out runs: the exact test still does not decide (its plain smallest p, 1/16, is
    // above 5 %), although its mid-p of "all four better" (1/32) would pass: with four of the
    // five runs of the shared sets that found D03's lag but added a false sensor mass on D09
    // (session 61). The paired t-test decides, sunk here by one run's large gain (D03's ratios
    // without its fifth run), as before.
    void fourRunsKeepThePairedTTest() {
        const std::vector<double> d = {0.39, 0.11, 0.08, 1.39};
        std::vector<double> w;
        for (double x : d) w.push_back(0.10 * std::exp(-x / 2));
        const ModelErrors ref = errors({0.10, 0.10, 0.10, 0.10}), with = errors(w);
        static const IdentifyOptions opt;
        Context cx;
        cx.opt = &opt;
        CandidateScore sc;
        sc.name = "frictional_lag";
        QVERIFY(!passesSelection(cx, sc, FitOutcome{}, ref, with, {}, {0, 1, 2, 3}, 1.0));
        QVERIFY(!sc.heldOutExact && !sc.heldOutMidP);
        QCOMPARE(sc.heldOutP, pairedLogRatioTest({1, 1, 1, 1}, {std::exp(-0.39), std::exp(-0.11), std::exp(-0.08), std::exp(-1.39)}).pValue);
        QVERIFY(sc.heldOutP > 0.05);
        QCOMPARE(sc.heldOutExactP, 1.0 / 16.0);
        QVERIFY2(sc.reason.find("paired t") != std::string::npos, sc.reason.c_str());
    }

    // Test (2b), relevance: every held-out run a little better is significant (p = 1/32) but not a
    // mechanism worth naming. The log MSE ratios are those of the false 6.4 g sensor mass on
    // `stickslip-cli synthesize --seed 6` (no effect; docs/identify-results.md, session 45): mean
    // 0.0048, i.e. 0.5 % of the held-out MSE. The same pattern ten times larger passes.
    void aConsistentButIrrelevantGainIsRejected() {
        const std::vector<double> d = {0.000319, 0.00353, 0.00827, 0.00623, 0.00587};
        auto with = [&](double scale) {
            std::vector<double> v;
            for (double x : d) v.push_back(0.10 * std::exp(-scale * x / 2));
            return errors(v);
        };
        const ModelErrors ref = errors({0.10, 0.10, 0.10, 0.10, 0.10});
        CandidateScore small;
        small.name = "sensor_inertia";
        QVERIFY(!select(small, ref, with(1.0)));
        QVERIFY2(std::abs(small.heldOutP - 1.0 / 64.0) < 1e-12, qPrintable(QString::number(small.heldOutP)));
        QVERIFY2(small.reason.find("below the relevance margin") != std::string::npos, small.reason.c_str());
        QVERIFY2(small.reason.find("0.5 %") != std::string::npos, small.reason.c_str());
        CandidateScore large;
        large.name = "sensor_inertia";
        QVERIFY2(select(large, ref, with(20.0)), large.reason.c_str());
        // The margin is an option: 0 is the significance test alone.
        IdentifyOptions off;
        off.minHeldOutGain = 0.0;
        Context cx;
        cx.opt = &off;
        CandidateScore again;
        again.name = "sensor_inertia";
        QVERIFY2(passesSelection(cx, again, FitOutcome{}, ref, with(1.0), {}, {0, 1, 2, 3, 4}, 1.0), again.reason.c_str());
        // No held-out run at all (one fit run): nothing to measure relevance on, so it does not decide.
        CandidateScore none;
        none.name = "sensor_inertia";
        ModelErrors noRuns;
        noRuns.validationNrmse = std::numeric_limits<double>::quiet_NaN();
        QVERIFY2(select(none, noRuns, noRuns), none.reason.c_str());
        QCOMPARE(none.heldOutUnits, 0);
    }

    // Which parameters the law run along the measured slip sees.
    // Selection test 0: the added effect whose size trades off most with the candidate's, when
    // the variance inflation 1/(1 − r²) exceeds the limit; NaN correlations decide nothing.
    void confoundedWithTakesTheLargestInflation() {
        CandidateScore sc;
        sc.sizeCorrelation = {{"a", 0.9}, {"b", -0.99}, {"c", 0.97}, {"mu", 0.999}};
        QCOMPARE(confoundedWith(sc, {"a"}, 10.0), std::string());         // VIF 5.3
        QCOMPARE(confoundedWith(sc, {"a", "c"}, 10.0), std::string("c"));  // VIF 16.9
        QCOMPARE(confoundedWith(sc, {"a", "b", "c"}, 10.0), std::string("b"));
        QCOMPARE(confoundedWith(sc, {"a", "b", "c"}, 100.0), std::string());
        QCOMPARE(confoundedWith(sc, {}, 10.0), std::string());  // baseline parameters (mu) are not effects
        sc.sizeCorrelation["b"] = std::numeric_limits<double>::quiet_NaN();
        QCOMPARE(confoundedWith(sc, {"b"}, 10.0), std::string());
        sc.sizeCorrelation["b"] = 1.0;
        QCOMPARE(confoundedWith(sc, {"b"}, 10.0), std::string("b"));
        // Equal inflation (correlations clamped to ±1): the first name in alphabetical order, in
        // whatever order the effects were added; the baseline's trade-off follows the same rule.
        sc.sizeCorrelation["c"] = -1.0;
        QCOMPARE(confoundedWith(sc, {"c", "b"}, 10.0), std::string("b"));
        CandidateScore base;
        base.sizeCorrelation = {{"mu", 1.0}, {"eta", -1.0}, {"normal_load_mu", 1.0}};
        QCOMPARE(baselineTradeOff(base, 10.0), std::string("eta"));
    }
    // The baseline parameter a candidate's size trades off with: the largest inflation above the
    // limit among keys that are neither effects nor effect parameters; NaN decides nothing.
    void baselineTradeOffSkipsEffectsAndTheirParameters() {
        CandidateScore sc;
        sc.sizeCorrelation = {{"normal_load_mu", 0.9999}, {"backlash.halfWidth_m", -0.9999}, {"mu", 0.96},
                              {"epsT", -0.99}, {"eta", std::numeric_limits<double>::quiet_NaN()}};
        QCOMPARE(baselineTradeOff(sc, 10.0), std::string("epsT"));  // VIF 50 beats mu's 12.8
        sc.sizeCorrelation["epsT"] = 0.5;
        QCOMPARE(baselineTradeOff(sc, 10.0), std::string("mu"));
        QCOMPARE(baselineTradeOff(sc, 20.0), std::string());
        sc.tradesOffWithBaseline = "mu";
        sc.reason = "dBIC = 1 is not below -10";
        QCOMPARE(verdictOf(sc), std::string("dBIC = 1 is not below -10; its size trades off with the baseline's mu "
                                            "(correlation 0.960): the data cannot tell the two apart"));
        sc.accepted = true;
        QVERIFY(verdictOf(sc).rfind("added; ", 0) == 0);
    }
    // The reports' note on a baseline trade-off: nothing unless the candidate trades off with a
    // baseline parameter (however large its correlations), else that parameter and its own
    // correlation (not another key's), sign kept, to three decimals.
    void baselineTradeOffTextNamesTheParameterAndItsCorrelation() {
        CandidateScore sc;
        sc.sizeCorrelation = {{"eta", -0.98765}, {"mu", 0.5}, {"epsT", 0.99999}};
        QCOMPARE(baselineTradeOffText(sc), std::string());
        sc.tradesOffWithBaseline = "eta";
        QCOMPARE(baselineTradeOffText(sc), std::string("its size trades off with the baseline's eta (correlation -0.988): "
                                                       "the data cannot tell the two apart"));
        sc.tradesOffWithBaseline = "mu";
        const std::string mu = baselineTradeOffText(sc);
        QVERIFY2(mu.find("the baseline's mu (correlation 0.500)") != std::string::npos, mu.c_str());
        // verdictOf is the reason followed by exactly this text.
        sc.reason = "dBIC = 2 is not below -10";
        QCOMPARE(verdictOf(sc), sc.reason + "; " + mu);
        sc.tradesOffWithBaseline.clear();
        QCOMPARE(verdictOf(sc), sc.reason);
    }
    // The baseline restart (IdentifyOptions::heldOutRestart) is taken only for a gain on the
    // evidence scale of an effect: the damper's marginal one (sum of squares 945.60 -> 944.84,
    // session 13) is not, a D16-like one (NRMSE 0.1336 -> 0.0404) is; no finite gain, no restart.
    void restartNeedsTheEffectMargin() {
        const double n = 1e5, cap = 300;
        const auto gain = [&](double ssFull, double ssPoint) { return bic(ssFull, n, cap, 6) - bic(ssPoint, n, cap, 6); };
        QVERIFY(std::abs(gain(945.60, 944.84) - cap * std::log(945.60 / 944.84)) < 1e-9);
        QVERIFY(!restartWorthIt(gain(945.60, 944.84), 10.0));
        QVERIFY(restartWorthIt(gain(945.60, 944.84), 0.0));
        QVERIFY(restartWorthIt(gain(n * 0.1336 * 0.1336, n * 0.0404 * 0.0404), 10.0));
        QVERIFY(!restartWorthIt(gain(1.0, 1.0), 0.0));
        QVERIFY(!restartWorthIt(std::numeric_limits<double>::quiet_NaN(), 0.0));
    }
    // After a candidate's restart the reported gain against the noise null is the refit's.
    void restartCreditsTheRefitsGain() {
        CandidateScore sc;
        sc.gain = 5.0;
        sc.nullReplicas = 200;
        creditRestartGain(sc, 100.0, 98.0);
        QCOMPARE(sc.gain, 7.0);
        creditRestartGain(sc, 98.0, std::numeric_limits<double>::quiet_NaN());
        QCOMPARE(sc.gain, 7.0);
        CandidateScore noNull;  // the null did not run: no gain to credit
        noNull.gain = 0.0;
        creditRestartGain(noNull, 100.0, 98.0);
        QCOMPARE(noNull.gain, 0.0);
    }
    // The loop's options: every one out of range is named with its value and allowed range, the
    // self-test's included; defaults are usable.
    void optionsNameEveryBadField() {
        IdentifyOptions o;
        QVERIFY(o.validate().empty());
        o.maxEffects = 0;
        o.nullReplicas = 0;
        QVERIFY(o.validate().empty());
        o.confoundedVif = 1.0;
        o.nullAlpha = 0.0;
        o.heldOutAlpha = 1.5;
        o.minHeldOutGain = 1.0;
        o.multistarts = 0;
        o.lineSearchSteps = 0;
        o.looFunctionTolerance = 0.0;
        o.selfTest.replicas = -3;
        const ParamIssues bad = o.validate();
        QCOMPARE(bad.size(), size_t(8));
        const std::string all = formatIssues(bad);
        for (const char* s : {"confounded_vif = 1 is out of range: must be > 1", "null_alpha = 0 is out of range: must be in (0, 1)",
                              "held_out_alpha = 1.5", "min_held_out_gain = 1 is out of range: must be in [0, 1)", "multistarts = 0 is out of range: must be >= 1",
                              "line_search_steps = 0 is out of range: must be >= 1", "replicas = -3",
                              "loo_function_tolerance = 0 is out of range: must be in (0, 0.01]"})
            QVERIFY2(all.find(s) != std::string::npos, qPrintable(QString::fromStdString(all)));
    }
    // The one cancel check every stage polls: false without a flag, then the flag's value.
    void cancelRequestedFollowsTheFlag() {
        // The free test (run_result.hpp), the run's and identify's members read one flag alike;
        // no flag is "never cancelled".
        IdentifyOptions o;
        RunControl ctl;
        QVERIFY(!o.cancelRequested());
        QVERIFY(!ctl.cancelled());
        QVERIFY(!stickslip::cancelRequested(nullptr));
        std::atomic<bool> stop{false};
        o.cancel = &stop;
        ctl.cancel = &stop;
        for (bool v : {false, true, false}) {
            stop = v;
            QCOMPARE(stickslip::cancelRequested(&stop), v);
            QCOMPARE(o.cancelRequested(), v);
            QCOMPARE(ctl.cancelled(), v);
        }
    }
    void lawParametersAreTheContactOnes() {
        for (const char* n : {"mu", "C1", "eta", "Dc", "vc", "epsT", "backlash.halfWidth_m", "frictional_lag.tau_s"})
            QVERIFY2(lawParameter(n), n);
        for (const char* n : {"m", "zeta", "viscous_damping.zeta", "sensor_inertia.mass_kg"}) QVERIFY2(!lawParameter(n), n);
    }

    // The damper (session 17): its runs are cut out of longer recordings (steady-amplitude trim),
    // so each starts with the contact loaded. identify ran the law from rest, which mispredicted
    // every run's first half-stroke (ε_T must be loaded through 2 F/ε_T of slip first) and cost
    // 0.05 of the damper's NRMSE (0.3147 against fit's 0.2656 on the same runs). A run cut out of
    // a longer recording now starts the law from its first measured force, in both set-ups. The
    // model that made the data must then leave no residual but α's transient, with and without
    // a dead band.
    void aRunCutMidStrokeStartsLoaded() {
        IdentifyOptions opt;
        opt.substeps = 4;
        Context cx;
        cx.opt = &opt;
        ExtendedModel m;
        m.law.mu = 0.30; m.law.C1 = 0.20; m.law.eta_s_per_m = 0.8; m.law.vc_mps = 0.1; m.law.Dc_m = 20e-6;
        m.law.epsT_N_per_m = 2e4;  // compliant: the loading from rest spans 2 µ t_N/ε_T ≈ 0.2 mm of slip
        m.tNref_N = 6.2;
        for (bool play : {false, true}) {
            if (play) m.effects.backlash = Backlash{5e-5};
            const IdentifyRun whole = syntheticRun(SetupKind::Prescribed);
            std::vector<double> t = whole.t_s, g = whole.slip_m, a = whole.accel_mps2;
            const ExtendedTrace tr = simulateExtendedPrescribed(m, {6.2, 0}, t, g, &a, opt.substeps);
            QVERIFY(tr.ok());
            // Cut at 0.4 s: mid-stroke, sliding (slip rate near its peak).
            const size_t cut = 400;
            IdentifyRun run = whole;
            auto tail = [cut](const std::vector<double>& v) { return std::vector<double>(v.begin() + cut, v.end()); };
            run.t_s = tail(whole.t_s);
            run.slip_m = tail(whole.slip_m);
            run.relVel_mps = tail(whole.relVel_mps);
            run.accel_mps2 = tail(whole.accel_mps2);
            run.force_N = tail(tr.measuredForce_N);
            run.cutFromRecording = true;
            QVERIFY(std::abs(run.force_N.front()) > 0.9 * m.law.mu * 6.2);  // loaded and sliding
            const Prepared p = prepared(run);
            std::vector<double> r;
            double ss = 0, n = 0;
            QVERIFY(runResiduals(cx, p, m, NAN, r, ss, n, nullptr, nullptr, nullptr, false));
            // Over the half-stroke the cut lands in: the model's own force but for the transient of
            // α, which is not measured and starts at 0 (it lasts D_c = 20 µm of slip, and its
            // strength offset stays through the elastic reload until the next slip). From rest the
            // residual there was 1.8 (the whole force). After the next slip: exact.
            double first = 0, later = 0;
            for (size_t i = 0; i < 100; ++i) first = std::max(first, std::abs(r[i]));
            for (size_t i = 100; i < r.size(); ++i) later = std::max(later, std::abs(r[i]));
            QVERIFY2(first < 0.1, qPrintable(QString("play %1: largest residual over the first 0.1 s %2 of the force RMS")
                                                 .arg(play).arg(first)));
            QVERIFY2(later < 1e-6, qPrintable(QString("play %1: largest residual after 0.1 s %2").arg(play).arg(later)));
        }
    }

    // A decimated run drives the law through its recorded slip: with decimation 4 and 2 law steps
    // per used sample, the steps end on every second recorded sample, so the law run equals the
    // one along the recorded slip at half the rate (to round-off in Δt), dwells' corners
    // included; the line between used samples, the old input, cuts them and differs.
    void decimatedRunIsDrivenThroughRecordedSlip() {
        IdentifyRun r = syntheticRun(SetupKind::Prescribed);
        for (size_t i = 0; i < r.t_s.size(); ++i) {  // dwells at the turning points
            const double s = 1.4 * std::sin(2 * M_PI * 3 * r.t_s[i]);
            r.slip_m[i] = 1e-3 * std::clamp(s, -1.0, 1.0);
        }
        IdentifyOptions opt;
        opt.decimate = 4;
        opt.substeps = 2;
        std::vector<IdentifyRun> runs = {r, r};
        runs[1].file = "second";
        Context cx;
        int dec = 0;
        std::string why;
        QVERIFY2(prepareContext(runs, opt, cx, dec, why), why.c_str());
        QCOMPARE(dec, 4);
        const Prepared& p = cx.runs[0];
        QCOMPARE(p.stepSlip.size(), (p.size() - 1) * 2);
        for (size_t i = 1; i < p.size(); ++i) {
            QCOMPARE(p.stepSlip[2 * (i - 1)], runs[0].slip_m[4 * (i - 1) + 2]);
            QCOMPARE(p.stepSlip[2 * (i - 1) + 1], p.g[i]);
        }
        ExtendedModel m;
        m.law.mu = 0.25; m.law.C1 = 0.2; m.law.eta_s_per_m = 0.6; m.law.Dc_m = 2e-5; m.law.vc_mps = 0.1;
        m.law.epsT_N_per_m = 5e4;
        LawRun law;
        QVERIFY(simulateLawRun(cx, p, m, law));
        std::vector<double> t2, g2;
        for (size_t i = 0; i < runs[0].t_s.size(); i += 2) {
            t2.push_back(runs[0].t_s[i]);
            g2.push_back(runs[0].slip_m[i]);
        }
        const ExtendedTrace half = simulateExtendedPrescribed(m, {r.normalForce_N, 0}, t2, g2, nullptr, 1);
        const ExtendedTrace line = simulateExtendedPrescribed(m, {r.normalForce_N, 0}, p.t, p.g, nullptr, 2);
        double worst = 0, lineWorst = 0;
        for (size_t i = 0; i < p.size(); ++i) {
            worst = std::max(worst, std::abs(law.contactForce_N[i] - half.contactForce_N[2 * i]));
            lineWorst = std::max(lineWorst, std::abs(line.contactForce_N[i] - half.contactForce_N[2 * i]));
        }
        qInfo("largest force difference to the half-rate recorded drive: %.2e N (line between used samples: %.2e N)", worst,
              lineWorst);
        QVERIFY(worst < 1e-9);
        QVERIFY(lineWorst > 1e-3);
        opt.recordedStepSlip = false;
        Context lin;
        QVERIFY2(prepareContext(runs, opt, lin, dec, why), why.c_str());
        QVERIFY(lin.runs[0].stepSlip.empty());
    }

    // The numerical part of the noise null (numericsOffset): with decimated runs it is the
    // residual at the used samples minus the residual of the same model predicted from every
    // recorded sample, read at the same samples and refitted there (linearised): what is left,
    // r0 − d, is the fine model's best-fit residual, orthogonal to its Jacobian's columns and no
    // larger than its residual at the coarse point. Without a recorded-rate context the fine model
    // has 4x the law steps along the recorded slip (here 8 per used interval, 2 per recorded one,
    // as the recorded-rate run).
    void numericsOffsetIsCoarseMinusRefittedFinePrediction() {
        IdentifyRun r = syntheticRun(SetupKind::Prescribed);
        for (size_t i = 0; i < r.t_s.size(); ++i) {
            const double s = 1.4 * std::sin(2 * M_PI * 3 * r.t_s[i]);
            r.slip_m[i] = 1e-3 * std::clamp(s, -1.0, 1.0);
        }
        IdentifyOptions opt, fullOpt;
        opt.start.mu = 0.25; opt.start.C1 = 0.2; opt.start.eta_s_per_m = 0.6; opt.start.Dc_m = 2e-5;
        opt.start.vc_mps = 0.1; opt.start.epsT_N_per_m = 5e4;
        opt.decimate = 4;
        fullOpt = opt;
        fullOpt.decimate = 1;
        std::vector<IdentifyRun> runs = {r, r};
        runs[1].file = "second";
        for (size_t i = 0; i < runs[1].force_N.size(); ++i) runs[1].force_N[i] += 0.3 * std::cos(91.0 * runs[1].t_s[i]);
        Context cx, full;
        int dec = 0;
        std::string why;
        QVERIFY2(prepareContext(runs, opt, cx, dec, why), why.c_str());
        QVERIFY2(prepareContext(runs, fullOpt, full, dec, why), why.c_str());
        QCOMPARE(dec, 1);
        cx.fullRate = &full;
        const Spec spec;
        const std::vector<size_t> idx = {0, 1};
        std::vector<double> r0, rf, d;
        QVERIFY(residualVector(cx, spec, {}, idx, r0));
        QVERIFY(residualVector(full, spec, {}, idx, rf));
        QVERIFY(numericsOffset(cx, spec, {}, idx, r0, d));
        const size_t nC = cx.runs[0].size(), nF = full.runs[0].size();
        QCOMPARE(r0.size(), 2 * nC);
        QCOMPARE(d.size(), r0.size());
        // The fine model's Jacobian at the used samples.
        const std::vector<FitParameter> ps = parameters(cx, spec, {});
        std::vector<std::string> names;
        for (const FitParameter& p : ps)
            if (p.free) names.push_back(p.name);
        QVERIFY(names.size() >= 5);
        const Eigen::MatrixXd Jf = residualJacobian(full, spec, {}, idx, ps, names, rf.size());
        Eigen::VectorXd left(static_cast<Eigen::Index>(r0.size())), atPoint(left.size());
        Eigen::MatrixXd Js(left.size(), Jf.cols());
        for (size_t run = 0; run < 2; ++run)
            for (size_t k = 0; k < nC; ++k) {
                const auto e = static_cast<Eigen::Index>(run * nC + k), f = static_cast<Eigen::Index>(run * nF + 4 * k);
                left[e] = r0[static_cast<size_t>(e)] - d[static_cast<size_t>(e)];
                atPoint[e] = rf[static_cast<size_t>(f)];
                Js.row(e) = Jf.row(f);
            }
        const double orth = (Js.transpose() * left).cwiseAbs().maxCoeff() / (Js.colwise().norm().maxCoeff() * left.norm());
        qInfo("refitted fine residual RMS %.3g (at the coarse point %.3g); largest cosine with a Jacobian column %.2e",
              left.norm() / std::sqrt(left.size()), atPoint.norm() / std::sqrt(left.size()), orth);
        QVERIFY(orth < 1e-8);
        QVERIFY(left.norm() <= atPoint.norm() * (1 + 1e-12));
        double dss = 0;
        for (double v : d) dss += v * v;
        QVERIFY(dss > 0);
        // Without the recorded-rate context: the law's steps refined 4x along the same input.
        cx.fullRate = nullptr;
        std::vector<double> dSub;
        QVERIFY(numericsOffset(cx, spec, {}, idx, r0, dSub));
        QCOMPARE(dSub.size(), r0.size());
        double sub = 0;
        for (double v : dSub) sub += v * v;
        qInfo("numerical part RMS: recorded rate %.3g, 4x the law steps %.3g", std::sqrt(dss / d.size()), std::sqrt(sub / d.size()));
        QVERIFY(sub > 0);
    }

    // A model that differs only in m, ζ, a viscous damping or a sensor mass may reuse another's law
    // run: the residuals are bit for bit those of its own simulation, in both set-ups; a model
    // with another law parameter is not (the test would see it).
    void sharedLawRunGivesIdenticalResiduals() {
        IdentifyOptions opt;
        Context cx;
        cx.opt = &opt;
        for (SetupKind setup : {SetupKind::Prescribed, SetupKind::Dynamics}) {
            const IdentifyRun run = syntheticRun(setup);
            const Prepared p = prepared(run);
            ExtendedModel a;
            a.law.mu = 0.25; a.law.C1 = 0.2; a.law.eta_s_per_m = 0.6; a.law.Dc_m = 2e-5; a.law.vc_mps = 0.1;
            a.law.epsT_N_per_m = 5e4;
            a.tNref_N = 6.2;
            ExtendedModel b = a;
            b.effects.viscousDamping = ViscousDamping{0.02};
            b.effects.sensorInertia = SensorInertia{0.01};
            LawRun lawA;
            QVERIFY(simulateLawRun(cx, p, a, lawA));
            std::vector<double> own, shared;
            double ss1 = 0, n1 = 0, ss2 = 0, n2 = 0;
            QVERIFY(runResiduals(cx, p, b, 0.5, own, ss1, n1, nullptr, nullptr, nullptr, false));
            QVERIFY(runResiduals(cx, p, b, 0.5, shared, ss2, n2, nullptr, nullptr, nullptr, false, &lawA));
            QCOMPARE(shared.size(), own.size());
            QVERIFY(own == shared);
            QCOMPARE(ss1, ss2);
            // ... and it is the force the extended model's own simulation has the sensor measure.
            if (setup == SetupKind::Prescribed) {
                std::vector<double> r, pred;
                QVERIFY(runResiduals(cx, p, b, 0.5, r, ss2, n2, &pred, nullptr, nullptr, false, &lawA));
                const ExtendedTrace tr = simulateExtendedPrescribed(b, {run.normalForce_N, 0}, p.t, p.g, &p.a, opt.substeps);
                QVERIFY(pred == tr.measuredForce_N);
            }
            // A different law: its residuals differ from the shared law run's.
            ExtendedModel c = b;
            c.law.mu = 0.26;
            std::vector<double> other;
            QVERIFY(runResiduals(cx, p, c, 0.5, other, ss1, n1, nullptr, nullptr, nullptr, false));
            QVERIFY(other != shared);
        }
    }
};

QTEST_APPLESS_MAIN(TestIdentifySelection)
#include "tst_identify_selection.moc"
