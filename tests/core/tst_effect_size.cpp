// The size test's quantity (identify_selection.cpp, effects/effect.hpp EffectSize): the runs'
// operating point, the healing's strength after the median stick, and the delta-method standard
// error when the leave-one-run-out fits are too few.
#include <QtTest/QtTest>

#include <cmath>
#include <limits>

#include "core/identify/effects/registry.hpp"
#include "core/identify/identify_internal.hpp"

using namespace stickslip;
using namespace stickslip::identify;
using namespace stickslip::identify::detail;

namespace {

// A prepared run at 1 kHz whose slip rate is 0 (stuck) on [a, b) for each (a, b) in `sticks`
// (sample indices) and 0.05 m/s elsewhere.
Prepared runWithSticks(const IdentifyRun& r, const std::vector<std::pair<int, int>>& sticks, int n) {
    Prepared p;
    p.run = &r;
    for (int i = 0; i < n; ++i) {
        p.t.push_back(1e-3 * i);
        bool stuck = false;
        for (const auto& [a, b] : sticks) stuck = stuck || (i >= a && i < b);
        p.V.push_back(stuck ? 0.0 : 0.05);
    }
    return p;
}

double healing(double b, double tc, double theta) { return b * std::log1p(theta / tc); }

}  // namespace

class TestEffectSize : public QObject {
    Q_OBJECT

private slots:
    // Only the stick episodes that begin after a slip and end in one count (a run that starts
    // stuck or ends stuck has an unknown or unfinished stick); validation runs do not count. The
    // median is weighted by duration: fragments a sample long (the slip rate's noise about the
    // stick threshold) do not move it.
    void operatingPointIsTheDurationWeightedMedianStick() {
        static const IdentifyOptions opt;
        IdentifyRun fitRun, valRun;
        valRun.validation = true;
        Context cx;
        cx.opt = &opt;
        // Run 1: starts stuck (0–100, not counted), sticks of 30 and 50 samples, ends stuck.
        cx.runs.push_back(runWithSticks(fitRun, {{0, 100}, {200, 230}, {400, 450}, {900, 1000}}, 1000));
        // Run 2: one stick of 80 samples and five fragments of 2.
        cx.runs.push_back(runWithSticks(fitRun, {{300, 380}, {500, 502}, {510, 512}, {520, 522}, {530, 532}, {540, 542}},
                                        1000));
        // A validation run's sticks of 1 s are not the fit runs'.
        cx.runs.push_back(runWithSticks(valRun, {{100, 1100}, {1200, 2200}}, 3000));
        // 170 ms stuck in all: in order of duration the fragments hold 10 ms, the 30 ms stick up
        // to 40, the 50 ms one up to 90, so it holds the 85th ms; the plain median of the eight
        // episodes would be a 2 ms fragment.
        QCOMPARE(operatingPoint(cx).stickDuration_s, 0.050);
        Context none;
        none.opt = &opt;
        none.runs.push_back(runWithSticks(fitRun, {}, 500));
        QVERIFY(std::isnan(operatingPoint(none).stickDuration_s));
    }

    // Leave-one-run-out fits that move along the healing's b–t_c valley (the same strength after
    // the runs' 50 ms sticks, b from 0.008 to 0.017) identify the healing: its size is that
    // strength. Judged by b alone, as before, the same fits leave it unidentified.
    void healingIsJudgedByItsStrengthAfterTheMedianStick() {
        static const IdentifyOptions opt;
        IdentifyRun r;
        Context cx;
        cx.opt = &opt;
        cx.runs.push_back(runWithSticks(r, {{100, 150}, {300, 350}, {500, 550}}, 1000));
        const double theta = 0.050, target = healing(0.0133, 0.0072, theta);
        auto point = [&](double b, double wobble) {
            // t_c that gives the target strength (× wobble) after a 50 ms stick.
            const double tc = theta / std::expm1(target * wobble / b);
            return std::map<std::string, double>{
                {"stick_healing.b_heal", b}, {"stick_healing.tc_s", tc}, {"stick_healing.Dh_m", 2e-5}};
        };
        FitOutcome fit;
        fit.values = point(0.0133, 1.0);
        fit.estimates.push_back({"stick_healing.b_heal", 0.0133, 1e-3});
        // The sixth refit gave no values (a failed refit): it is left out, not an error.
        const std::vector<std::map<std::string, double>> loo = {point(0.0081, 1.05), point(0.0149, 0.98),
                                                                point(0.0159, 0.95), point(0.0171, 1.02),
                                                                point(0.0132, 1.0), {}};
        CandidateScore sc;
        sc.name = "stick_healing";
        QVERIFY2(passesSizeTest(cx, sc, fit, loo, 1.0), sc.reason.c_str());
        QVERIFY2(sc.sizeParam.find("strength_after_median_stick") != std::string::npos, sc.sizeParam.c_str());
        QVERIFY(std::abs(sc.sizeValue - target) < 1e-12);
        QCOMPARE(sc.sizeNull, 0.0);
        QVERIFY2(sc.sizeStderrKind.find("jackknife over 5 ") != std::string::npos, sc.sizeStderrKind.c_str());
        // No complete stick in the fit runs: no operating point, b decides, and fails.
        Context bare;
        bare.opt = &opt;
        IdentifyRun sliding;
        bare.runs.push_back(runWithSticks(sliding, {}, 1000));
        CandidateScore byB;
        byB.name = "stick_healing";
        QVERIFY(!passesSizeTest(bare, byB, fit, loo, 1.0));
        QCOMPARE(QString::fromStdString(byB.sizeParam), QString("b_heal"));
        QVERIFY2(byB.reason.find("is not identified") != std::string::npos, byB.reason.c_str());
    }

    // paramOr: the value when present, NaN (never a throw, never a default that looks like a
    // measurement) when a refit gave no values for the name.
    void paramOrIsNaNForAMissingName() {
        const std::map<std::string, double> p{{"b_heal", 0.012}, {"tc_s", 0.0}};
        QCOMPARE(paramOr(p, "b_heal"), 0.012);
        QCOMPARE(paramOr(p, "tc_s"), 0.0);
        QVERIFY(std::isnan(paramOr(p, "Dh_m")));
        QVERIFY(std::isnan(paramOr({}, "b_heal")));
    }

    // Fewer than three leave-one-run-out fits: the Jacobian's standard error of the strength by
    // the delta method, g' Σ g with Σ from the fit's standard errors and correlations, × sqrt(τ).
    void strengthStderrIsTheDeltaMethodsWithoutRefits() {
        static const IdentifyOptions opt;
        IdentifyRun r;
        Context cx;
        cx.opt = &opt;
        cx.runs.push_back(runWithSticks(r, {{100, 150}, {300, 350}}, 1000));
        const double b = 0.0133, tc = 0.0072, theta = 0.050, sb = 1e-3, st = 2e-3, rho = 0.6, tau = 4.0;
        FitOutcome fit;
        fit.values = {{"mu", 0.26}, {"stick_healing.b_heal", b}, {"stick_healing.tc_s", tc},
                      {"stick_healing.Dh_m", 2e-5}};
        FitResult& fr = fit.fit;
        fr.names = {"mu", "stick_healing.b_heal", "stick_healing.tc_s", "stick_healing.Dh_m"};
        fr.stderrs = {0.01, sb, st, 0.0};
        fr.freeNames = {"mu", "stick_healing.b_heal", "stick_healing.tc_s"};
        fr.correlation = {1, 0.3, 0.1, 0.3, 1, rho, 0.1, rho, 1};
        CandidateScore sc;
        sc.name = "stick_healing";
        passesSizeTest(cx, sc, fit, {}, tau);
        const double gb = std::log1p(theta / tc), gt = -b * theta / (tc * tc) / (1.0 + theta / tc);
        const double expected = std::sqrt(gb * gb * sb * sb + gt * gt * st * st + 2 * gb * gt * sb * st * rho) * 2.0;
        QVERIFY2(std::abs(sc.sizeStderr - expected) < 1e-6 * expected,
                 qPrintable(QString("%1 vs %2").arg(sc.sizeStderr).arg(expected)));
        QVERIFY2(sc.sizeStderrKind.find("delta method") != std::string::npos, sc.sizeStderrKind.c_str());
    }
};

QTEST_APPLESS_MAIN(TestEffectSize)
#include "tst_effect_size.moc"
