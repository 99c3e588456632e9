// The sums of squares behind the candidates' scanned starts and the restart guards
// (identify_residuals.cpp evalSS, identify_fit.cpp scannedStart): a sum stopped once it passes a
// bound is a lower bound above it and never changes which point is lowest. Prescribed runs made
// by the project's own simulator (identify_synth.hpp).
#include <QtTest/QtTest>

#include <cmath>
#include <limits>

#include "core/identify/identify_internal.hpp"
#include "identify_synth.hpp"

using namespace stickslip;
using namespace stickslip::identify;
using namespace stickslip::identify::detail;

namespace {

struct Fixture {
    IdentifyOptions opt = synth::testOptions();
    std::vector<IdentifyRun> runs;
    Context cx;
    std::vector<size_t> idx;
    std::map<std::string, double> start;

    bool make(const ExtendedModel& truth, std::string& why) {
        runs = synth::makeRuns(truth, 1.5, 0.02, 3);
        int dec = 0;
        if (!prepareContext(runs, opt, cx, dec, why)) return false;
        for (size_t i = 0; i < runs.size(); ++i) idx.push_back(i);
        // The law at the truth's values: the scan then looks for the effect alone.
        start = {{"mu", truth.law.mu}, {"C1", truth.law.C1}, {"eta", truth.law.eta_s_per_m}, {"vc", truth.law.vc_mps}};
        return true;
    }
};

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

class TestIdentifyScan : public QObject {
    Q_OBJECT
private slots:
    // Without a bound (or with one the full sum does not pass) evalSS is the full sum to the last
    // bit; with one, it stops after the first run that passes it and returns that partial sum.
    void evalSSStopsAfterTheRunThatPassesTheBound() {
        Fixture fx;
        std::string why;
        QVERIFY2(fx.make(synth::trueModel(), why), why.c_str());
        QCOMPARE(fx.idx.size(), size_t{4});
        const Spec spec;
        const double full = evalSS(fx.cx, spec, fx.start, fx.idx);
        QVERIFY(std::isfinite(full) && full > 0);
        QCOMPARE(evalSS(fx.cx, spec, fx.start, fx.idx, kInf), full);
        QCOMPARE(evalSS(fx.cx, spec, fx.start, fx.idx, full), full);  // equal is not above
        // Partial sums run by run, as the full one adds them.
        std::vector<double> upTo;
        double acc = 0;
        for (size_t i : fx.idx) upTo.push_back(acc += evalSS(fx.cx, spec, fx.start, {i}));
        QCOMPARE(upTo.back(), full);
        QVERIFY(upTo.front() < full);
        // A bound below the first run's sum: stopped after it.
        QCOMPARE(evalSS(fx.cx, spec, fx.start, fx.idx, 0.5 * upTo[0]), upTo[0]);
        // A bound between the second and third partial sums: stopped after the third run.
        const double between = 0.5 * (upTo[1] + upTo[2]);
        const double stopped = evalSS(fx.cx, spec, fx.start, fx.idx, between);
        QCOMPARE(stopped, upTo[2]);
        QVERIFY(stopped > between && stopped <= full);
    }

    // The scan keeps the lowest of its points by their full sums: the point it returns fits at
    // least as well as every value of the effect's own grid (9 log values across its range) and
    // its start, each evaluated in full here, although the scan abandoned most of them early.
    void scannedStartKeepsTheLowestFullSum() {
        ExtendedModel truth = synth::trueModel();
        truth.effects.frictionalLag = FrictionalLag{4e-3};
        Fixture fx;
        std::string why;
        QVERIFY2(fx.make(truth, why), why.c_str());
        Spec spec;
        spec.effects = {"frictional_lag"};
        const std::map<std::string, double> st = scannedStart(fx.cx, spec, "frictional_lag", fx.start, fx.idx);
        const double chosen = evalSS(fx.cx, spec, st, fx.idx);
        QVERIFY(std::isfinite(chosen));
        EffectInfo info;
        QVERIFY(findEffect("frictional_lag", info));
        const EffectParam q = scaledParam(info.params.front(), fx.cx.muScale);
        const std::string key = "frictional_lag." + q.name;
        std::map<std::string, double> v = effectStart(fx.cx, "frictional_lag", fx.start);
        double lowest = evalSS(fx.cx, spec, v, fx.idx);
        for (int k = 0; k < 9; ++k) {
            v[key] = q.lower * std::pow(q.upper / q.lower, k / 8.0);
            lowest = std::min(lowest, evalSS(fx.cx, spec, v, fx.idx));
        }
        qInfo("scan chose tau = %.3g s at SS %.6g; lowest of the grid in full %.6g", st.at(key), chosen, lowest);
        QCOMPARE(chosen, lowest);
        // And it is one of the two grid values around the truth's 4 ms (within one log step).
        QVERIFY(std::abs(std::log(st.at(key) / 4e-3)) <= std::log(q.upper / q.lower) / 8.0 + 1e-12);
    }
};

QTEST_APPLESS_MAIN(TestIdentifyScan)
#include "tst_identify_scan.moc"
