// Convergence of the fixed-step scheme under step refinement: Fig. 20 set, A = 1 mm, 20 forcing
// cycles from rest; slider-displacement error against the same run at dt/64.
#include <QtTest>

#include <cmath>
#include <vector>

#include "core/integrate/dynamics.hpp"
#include "physics_helpers.hpp"

using namespace stickslip;
using namespace stickslip::testing;

namespace {

// x(t) at every T/100 over 20 cycles with `stepsPerCycle` steps per forcing period.
std::vector<double> sliderTrace(SimParams p, long stepsPerCycle) {
    p.integration.dt_s = p.drive.period() / static_cast<double>(stepsPerCycle);
    p.integration.outputInterval_s = p.drive.period() / 100.0;
    p.cycles = 20;
    const RunResult r = simulateDynamics(p);
    std::vector<double> x;
    if (!r.ok()) return x;
    for (const Sample& s : r.samples) x.push_back(s.slider_m);
    return x;
}

}  // namespace

class TstConvergence : public QObject {
    Q_OBJECT
private slots:
    // Levels: 1000, 2000, 4000, 8000 steps per cycle (dt = T/1000 … T/8000); reference: the
    // same run at dt/64 = T/64 000, i.e. still 8× finer than the finest level. Error: the
    // largest |x − x_ref| over all output samples, relative to the largest |x_ref|.
    //
    // Expected order: 1. Newmark is second order for smooth motion, but the stick–slip switches
    // are not located inside the step, which costs O(h) at every switch (MODEL.md: first
    // order; 1e-3 needs ~10 000 steps per cycle). Below ~1000 steps per cycle the run is not in
    // the asymptotic range (the stuck mode sqrt((k+ε_T)/m) ≈ 1380 rad/s gets < 7 steps per
    // period at 500; measured pairwise order 500 → 1000 only 0.6, at 250 the error is O(1)),
    // so the levels start at 1000. We assert a lower bound only, 0.8 on the least-squares
    // slope of log(error) against log(dt), so an improved scheme (e.g. switch location) passes;
    // and that the error falls monotonically. Both fail for a scheme that does not converge or
    // converges at a lower order (e.g. a lagged, explicit coupling of the law).
    void observedOrder_data() {
        QTest::addColumn<bool>("coulomb");
        QTest::addRow("rate-state") << false;
        QTest::addRow("coulomb") << true;
    }
    void observedOrder() {
        QFETCH(bool, coulomb);
        SimParams p = fig20Params();
        p.law = coulomb ? LawKind::Coulomb : LawKind::RateState;
        const std::vector<long> levels = {1000, 2000, 4000, 8000};
        const std::vector<double> ref = sliderTrace(p, 64 * levels.front());
        QCOMPARE(ref.size(), size_t(20 * 100 + 1));
        double amp = 0;
        for (double v : ref) amp = std::max(amp, std::abs(v));
        QVERIFY(amp > 1e-4);  // the slider really moves (sub-mm)
        std::vector<double> err;
        for (long n : levels) {
            const std::vector<double> x = sliderTrace(p, n);
            QCOMPARE(x.size(), ref.size());
            double e = 0;
            for (size_t i = 0; i < x.size(); ++i) e = std::max(e, std::abs(x[i] - ref[i]));
            err.push_back(e / amp);
        }
        // Least-squares slope of log e against log dt (dt halves from level to level).
        double sx = 0, sy = 0, sxx = 0, sxy = 0;
        const double m = static_cast<double>(levels.size());
        for (size_t i = 0; i < levels.size(); ++i) {
            const double lx = std::log(1.0 / static_cast<double>(levels[i])), ly = std::log(err[i]);
            sx += lx; sy += ly; sxx += lx * lx; sxy += lx * ly;
        }
        const double order = (m * sxy - sx * sy) / (m * sxx - sx * sx);
        for (size_t i = 0; i < levels.size(); ++i)
            qInfo("%s: %5ld steps/cycle: error %.4g of amplitude%s", coulomb ? "coulomb" : "rate-state", levels[i], err[i],
                  i > 0 ? qPrintable(QString(", pairwise order %1").arg(std::log2(err[i - 1] / err[i]), 0, 'f', 2)) : "");
        qInfo("%s: observed order (least squares over %zu levels) = %.3f", coulomb ? "coulomb" : "rate-state",
              levels.size(), order);
        for (size_t i = 1; i < err.size(); ++i)
            QVERIFY2(err[i] < err[i - 1], qPrintable(QString("error grew from %1 to %2").arg(err[i - 1]).arg(err[i])));
        QVERIFY2(order >= 0.8, qPrintable(QString("observed order %1").arg(order)));
    }
};

QTEST_GUILESS_MAIN(TstConvergence)
#include "tst_convergence.moc"
