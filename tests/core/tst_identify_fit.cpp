// fitSpec (identify_fit.cpp), the identify loop's one fit of a model to runs: its second pass in
// the law's own coordinates C1, η, v_c is for fits in the steady-state curve's coordinates that
// met the edge of their feasible region, not for those that start at their optimum. Prescribed
// runs made by the project's own simulator (identify_synth.hpp).
#include <QtTest/QtTest>

#include <cmath>

#include "core/identify/identify_internal.hpp"
#include "identify_synth.hpp"

using namespace stickslip;
using namespace stickslip::identify;
using namespace stickslip::identify::detail;

class TestIdentifyFit : public QObject {
    Q_OBJECT
private slots:
    // A refit from the optimum a fit already reached ends where it started. Session 51 measured
    // 15 such fits on D13 and D05 each done a second time in C1, η, v_c, every one ending at
    // exactly the same sum of squares: at a stationary point a second coordinate system finds
    // nothing the first did not. It is one fit, and the curve coordinates never left C1's and
    // η's bounds.
    void aStartAtItsOptimumIsFittedOnce() {
        IdentifyOptions opt = synth::testOptions();
        std::vector<IdentifyRun> runs = synth::makeRuns(synth::trueModel(), 2.0, 0.02, 1);
        Context cx;
        int dec = 0;
        std::string why;
        QVERIFY2(prepareContext(runs, opt, cx, dec, why), why.c_str());
        QVERIFY(opt.curveCoordinates);
        const std::vector<size_t> idx = {0, 1, 2, 3};
        const Spec spec;
        long fits = 0;
        FitOutcome f = fitSpec(cx, spec, baselineStart(cx, idx), idx, 1, fits, true);
        QVERIFY2(f.ok, f.message.c_str());
        // Refit until a refit no longer moves (the optimum to the solver's tolerances).
        bool stalled = false;
        for (int k = 0; k < 6 && !stalled; ++k) {
            const long before = fits;
            FitOutcome g = fitSpec(cx, spec, f.values, idx, 1, fits);
            QVERIFY2(g.ok, g.message.c_str());
            stalled = !(g.fit.cost < g.fit.initialCost * (1.0 - 1e-12));
            qInfo("refit %d: ss %.9g -> %.9g, %ld fit(s), %ld outside the law's bounds, stalled %d", k, f.ss, g.ss,
                  fits - before, g.outsideLawBounds, int(stalled));
            if (stalled) {
                QCOMPARE(g.outsideLawBounds, 0L);
                QCOMPARE(fits - before, 1L);
                QCOMPARE(g.ss, f.ss);
            }
            QVERIFY(g.ss <= f.ss * (1.0 + 1e-12));
            f = std::move(g);
        }
        QVERIFY2(stalled, "no refit ended at its start: the premise of this test does not hold");
    }
};

QTEST_APPLESS_MAIN(TestIdentifyFit)
#include "tst_identify_fit.moc"
