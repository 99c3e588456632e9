// Poincaré sections, sweeps and maps with error-controlled steps (section_stepping.hpp,
// issue 15 items 2-4): samples at the exact forcing phase from the dense output, agreement
// with a fine fixed-step section, and the sweep's classification unchanged against the
// fixed-step sweep of the paper's algorithm.
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/analysis/periodicity_map.hpp"
#include "core/analysis/poincare.hpp"
#include "core/analysis/section_stepping.hpp"
#include "core/analysis/sweep.hpp"
#include "core/presets.hpp"

using namespace stickslip;

namespace {
SimParams fig20() {
    Preset p;
    if (!findPreset("fig20", p)) qFatal("no preset fig20");
    return p.params;
}
double maxAbs(const std::vector<double>& v) {
    double m = 0;
    for (double x : v) m = std::max(m, std::abs(x));
    return m;
}
}  // namespace

class TstSectionAdaptive : public QObject {
    Q_OBJECT
private slots:
    // Fixed N stays the paper's map; a tolerance selects the adaptive stepping with N kept as
    // the nominal count and the phase time exact.
    void steppingFollowsTheTolerance() {
        SimParams p = fig20();
        SectionStepping st = SectionStepping::of(p, 1000);
        QVERIFY(!st.adaptive);
        QCOMPARE(st.stepsPerPeriod, 1000L);
        const double T = p.drive.period();
        QCOMPARE(st.phaseTime(1.0), std::round(1.0 / (2 * std::numbers::pi) * 1000) * (T / 1000));
        p.integration.tolerance = 1e-4;
        st = SectionStepping::of(p, 1000);
        QVERIFY(st.adaptive);
        QCOMPARE(st.options.tolerance, 1e-4);
        QCOMPARE(st.phaseTime(1.0), 1.0 / (2 * std::numbers::pi) * T);
    }

    // On a period-1 orbit (A = 0.5 mm) the adaptive section samples exactly t = (settle + k)T and
    // agrees with a fine fixed-step section (T/64000) to the tolerance's order in x; stick
    // fraction and max |V| agree too.
    void adaptiveSectionMatchesAFineFixedStep() {
        SimParams p = fig20();
        p.drive.amplitude_m = 0.5e-3;
        PoincareOptions o;
        o.settleCycles = 20;
        o.cycles = 8;
        o.stepsPerPeriod = 64000;
        const PoincareSection ref = poincareSection(p, o);
        QVERIFY2(ref.ok(), ref.message.c_str());
        const double T = p.drive.period(), scale = maxAbs(ref.slider_m);
        for (double tol : {1e-4, 1e-5}) {
            p.integration.tolerance = tol;
            const PoincareSection ad = poincareSection(p, o);
            QVERIFY2(ad.ok(), ad.message.c_str());
            QCOMPARE(ad.size(), ref.size());
            double err = 0;
            for (std::size_t i = 0; i < ad.size(); ++i) {
                QVERIFY(std::abs(ad.t_s[i] - (20 + 1 + static_cast<double>(i)) * T) < 1e-9 * T);
                err = std::max(err, std::abs(ad.slider_m[i] - ref.slider_m[i]) / scale);
            }
            qInfo("TOL %g vs T/64000, A = 0.5 mm: max |dx| / max|x| = %.3g, stick fraction %.4f vs %.4f, "
                  "max |V| %.5g vs %.5g", tol, err, ad.stickFraction, ref.stickFraction, ad.maxRelVel_mps,
                  ref.maxRelVel_mps);
            QVERIFY(err < 10 * tol);
            QVERIFY(std::abs(ad.stickFraction - ref.stickFraction) < 0.01);
            QVERIFY(ad.slipSteps > 0);
            QVERIFY(std::abs(ad.maxRelVel_mps - ref.maxRelVel_mps) < 0.01 * ref.maxRelVel_mps);
        }
    }

    // A phase that no step of the fixed grid reaches: the samples are at the exact phase.
    void adaptiveSectionAtAnyPhase() {
        SimParams p = fig20();
        p.integration.tolerance = 1e-4;
        PoincareOptions o;
        o.settleCycles = 3;
        o.cycles = 4;
        o.phase_rad = 1.0;
        const PoincareSection s = poincareSection(p, o);
        QVERIFY2(s.ok(), s.message.c_str());
        const double T = p.drive.period(), t0 = 1.0 / (2 * std::numbers::pi) * T;
        QCOMPARE(s.size(), std::size_t(4));
        for (std::size_t i = 0; i < s.size(); ++i) QVERIFY(std::abs(s.t_s[i] - (t0 + (4.0 + i) * T)) < 1e-11);
    }

    // The sweep's classification with the adaptive stepping against the paper's fixed step
    // T/8000, on both branches of a continuation and in the independent mode, over the period-1
    // windows of the Fig. 20 amplitude range (A = 0.5, 1.0, 3.5 mm). Near bifurcations and in the
    // irregular windows the two differ (docs/adaptive.md: the adaptive map is not exactly
    // T-periodic, its section points jitter at the tolerance's order, and irregular motion
    // amplifies any difference); this test does not claim those values.
    void sweepClassificationMatchesFixedStep() {
        SimParams p = fig20();
        SweepOptions so;
        so.key = "A";
        so.from = 0.5e-3;
        so.to = 3.5e-3;
        so.steps = 7;
        so.settleCycles = 50;
        so.sampleCycles = 60;
        so.stepsPerPeriod = 8000;
        so.lyapunov = false;
        so.direction = SweepDirection::Both;
        for (SweepMode mode : {SweepMode::Continuation, SweepMode::Independent}) {
            so.mode = mode;
            p.integration.tolerance = 0;
            const SweepResult fixed = bifurcationSweep(p, so);
            p.integration.tolerance = 1e-4;
            const SweepResult ad = bifurcationSweep(p, so);
            QVERIFY2(fixed.status == RunStatus::Ok, fixed.message.c_str());
            QVERIFY2(ad.status == RunStatus::Ok, ad.message.c_str());
            QCOMPARE(ad.points.size(), fixed.points.size());
            int compared = 0;
            for (std::size_t i = 0; i < ad.points.size(); ++i) {
                const Classification& a = ad.points[i].classification;
                const Classification& f = fixed.points[i].classification;
                const double mm = ad.points[i].value * 1e3;
                QCOMPARE(ad.points[i].value, fixed.points[i].value);
                qInfo("%s A = %.3g mm %s: T/8000 %s/%d, adaptive 1e-4 %s/%d", toString(mode), mm,
                      ad.points[i].direction > 0 ? "up" : "down", toString(f.motion), f.period, toString(a.motion),
                      a.period);
                if (!(std::abs(mm - 0.5) < 1e-9 || std::abs(mm - 1.0) < 1e-9 || std::abs(mm - 3.5) < 1e-9)) continue;
                ++compared;
                QVERIFY(f.motion == MotionClass::Periodic && f.period == 1);
                QVERIFY(a.motion == f.motion);
                QCOMPARE(a.period, f.period);
                QVERIFY(std::abs(a.stickFraction - f.stickFraction) < 0.02);
            }
            QCOMPARE(compared, 6);
        }
    }

    // Where the adaptive sweep and the paper's fixed step disagree, a fine fixed step (T/128000,
    // first order, so ~13x closer to the exact motion than the preset's T/10000) sides with the
    // adaptive one: the differences are the fixed step's error, not the adaptive step's.
    // Measured on the whole range (docs/adaptive.md, session 44; 60 values A = 0.1-5 mm,
    // independent, 50 settle + 100 sampled cycles): against T/128000, T/10000 agrees on 48,
    // TOL 1e-3 on 53, TOL 1e-4 and 1e-5 on 55. Two of those values here: A = 3.09 mm (period 1;
    // T/10000 sees irregular motion) and A = 1.68 mm (irregular; T/10000 finds period 2).
    void adaptiveSidesWithFineStepWhereFixedStepDiffers() {
        SimParams p = fig20();
        SweepOptions so;
        so.key = "A";
        so.steps = 1;
        so.settleCycles = 50;
        so.sampleCycles = 100;
        so.lyapunov = false;
        so.mode = SweepMode::Independent;
        so.direction = SweepDirection::Up;
        const double T = p.drive.period();
        const long presetN = std::lround(T / p.integration.dt_s);
        struct Case { double A_m; MotionClass motion; int period; };
        for (const Case c : {Case{0.1e-3 + 36 * (4.9e-3 / 59), MotionClass::Periodic, 1},
                             Case{0.1e-3 + 19 * (4.9e-3 / 59), MotionClass::Irregular, 0}}) {
            so.from = so.to = c.A_m;
            auto classOf = [&](double tol, long n) {
                p.integration.tolerance = tol;
                so.stepsPerPeriod = n;
                const SweepResult r = bifurcationSweep(p, so);
                if (r.status != RunStatus::Ok || r.points.size() != 1) qFatal("sweep failed: %s", r.message.c_str());
                return r.points[0].classification;
            };
            const Classification fine = classOf(0, 128000), fixed = classOf(0, presetN), ad = classOf(1e-4, presetN);
            qInfo("A = %.4g mm: T/128000 %s/%d (best mismatch %.3g), T/%ld %s/%d, adaptive 1e-4 %s/%d", c.A_m * 1e3,
                  toString(fine.motion), fine.period, fine.bestMismatch, presetN, toString(fixed.motion), fixed.period,
                  toString(ad.motion), ad.period);
            QVERIFY(fine.motion == c.motion);
            QCOMPARE(fine.period, c.period);
            QVERIFY(ad.motion == fine.motion);
            QCOMPARE(ad.period, fine.period);
            QVERIFY(fixed.motion != fine.motion || fixed.period != fine.period);
        }
    }

    // Period-1 map cells with a tolerance are classified as with the fixed step.
    void mapCellsMatchFixedStep() {
        SimParams p = fig20();
        MapOptions mo;
        mo.key1 = "A";
        mo.from1 = 0.5e-3;  // period-1 cells
        mo.to1 = 1e-3;
        mo.steps1 = 2;
        mo.key2 = "f";
        mo.from2 = 2.5;
        mo.to2 = 3.5;
        mo.steps2 = 2;
        // 100 settle cycles: with 40 the adaptive runs of the (1 mm, 2.5 Hz) cell are not yet
        // within the period test's 1e-4 (irregular at TOL 1e-4, period 5 at 1e-5; T/8000 and
        // T/64000 are period 1 already): their approach to the orbit is slower (docs/adaptive.md).
        mo.settleCycles = 100;
        mo.sampleCycles = 40;
        mo.stepsPerPeriod = 8000;
        const PeriodicityMap fixed = periodicityMap(p, mo);
        p.integration.tolerance = 1e-4;
        const PeriodicityMap ad = periodicityMap(p, mo);
        QVERIFY2(fixed.status == RunStatus::Ok && ad.status == RunStatus::Ok, (fixed.message + ad.message).c_str());
        QCOMPARE(ad.motion.size(), fixed.motion.size());
        for (std::size_t k = 0; k < ad.motion.size(); ++k) {
            qInfo("cell %zu: T/8000 %s/%d, adaptive 1e-4 %s/%d", k, toString(fixed.motion[k]), fixed.period[k],
                  toString(ad.motion[k]), ad.period[k]);
            QVERIFY(ad.motion[k] == fixed.motion[k]);
            QCOMPARE(ad.period[k], fixed.period[k]);
        }
    }

    // The Lyapunov companion steps the fixed-step map: a sweep asking for both is refused,
    // naming the tolerance.
    void lyapunovWithAToleranceIsRefused() {
        SimParams p = fig20();
        p.integration.tolerance = 1e-4;
        SweepOptions so;
        so.lyapunov = true;
        const ParamIssues bad = so.validate(p);
        QCOMPARE(bad.size(), std::size_t(1));
        QCOMPARE(bad.front().field, std::string("tolerance"));
        so.lyapunov = false;
        QVERIFY(so.validate(p).empty());
    }
};

QTEST_APPLESS_MAIN(TstSectionAdaptive)
#include "tst_section_adaptive.moc"
