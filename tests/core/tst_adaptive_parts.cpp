// The adaptive stepper's parts (core/integrate/adaptive.hpp, issue 15): the closed-form stuck
// step, TR-BDF2's embedded error estimate, the Illinois root of the switch location, the dense
// output, options validation, and failure and cancellation as statuses. The stepper as a whole
// (order, error against tolerance, located switches, energy) is in tst_adaptive.cpp.
#include <QtTest>

#include <atomic>
#include <cmath>
#include <vector>

#include "core/integrate/adaptive.hpp"
#include "core/integrate/illinois.hpp"
#include "core/integrate/stuck_flow.hpp"
#include "core/integrate/trbdf2.hpp"
#include "physics_helpers.hpp"

using namespace stickslip;
using namespace stickslip::testing;

class TstAdaptiveParts : public QObject {
    Q_OBJECT
private slots:
    // Closed-form stick (stuck_flow.hpp): the motion it gives is Eq. 8 with the elastic law
    // (F − ε_T (u − x) constant, ẍ the equilibrium and the derivative of ẋ), steps compose
    // (τ1 then τ2 = τ1 + τ2), and a run that sticks throughout (the Fig. 20 set at A = 0.05 mm, far
    // below its stick threshold, from rest: the stuck mode rings) agrees with the scheme's own stuck steps at
    // TOL 1e-5 in x and F, in a fraction of the steps.
    void closedFormStick() {
        SimParams p = lawParams(false, 3);
        p.drive.amplitude_m = 0.05e-3;
        const DynamicsModel m = DynamicsModel::fromParams(p);
        const double eps = p.lawParams<RateStateParams>().epsT_N_per_m;
        const detail::StuckFlow f(p.rig, eps, m.stage);
        QVERIFY(f.valid());
        DynState s = m.initialState(0.013);
        s.x = 1e-5;
        s.v = 2e-3;
        s.law.force_N = 0.3;
        s.a = (s.law.force_N - p.rig.damping_Ns_per_m * s.v - p.rig.stiffness_N_per_m * s.x) / p.rig.mass_kg;
        const double tau = 1.7e-3, d = 1e-7;
        const DynState y = f.advance(s, f.split(s), tau);
        const DynState y1 = f.advance(s, f.split(s), 0.6e-3);
        const DynState y2 = f.advance(y1, f.split(y1), tau - 0.6e-3);
        QVERIFY(std::abs(y.t - (s.t + tau)) <= 1e-15);
        QVERIFY2(std::abs(y2.x - y.x) <= 1e-12 * std::abs(y.x) + 1e-18, qPrintable(QString("%1 vs %2").arg(y2.x).arg(y.x)));
        QVERIFY(std::abs(y2.v - y.v) <= 1e-10 * std::abs(y.v) + 1e-15);
        QVERIFY(std::abs(y.u - m.stage.displacement(y.t)) <= 1e-15);
        QVERIFY(std::abs((y.law.force_N - eps * (y.u - y.x)) - (s.law.force_N - eps * (s.u - s.x))) <= 1e-9);
        const DynState ya = f.advance(s, f.split(s), tau - d), yb = f.advance(s, f.split(s), tau + d);
        QVERIFY2(std::abs((yb.v - ya.v) / (2 * d) - y.a) <= 1e-5 * std::abs(y.a),
                 qPrintable(QString("dv/dt %1 vs a %2").arg((yb.v - ya.v) / (2 * d)).arg(y.a)));
        QVERIFY(std::abs((yb.x - ya.x) / (2 * d) - y.v) <= 1e-5 * std::abs(y.v));

        AdaptiveOptions o;
        o.tolerance = 1e-5;
        const RunResult a = simulateAdaptive(p, o);
        o.closedFormStick = false;
        const RunResult b = simulateAdaptive(p, o);
        QVERIFY2(a.ok() && b.ok(), (a.message + b.message).c_str());
        QCOMPARE(a.stats.stuckSteps, a.stats.steps);
        QCOMPARE(a.samples.size(), b.samples.size());
        double dx = 0, dF = 0, xMax = 0, FMax = 0;
        for (size_t i = 0; i < a.samples.size(); ++i) {
            dx = std::max(dx, std::abs(a.samples[i].slider_m - b.samples[i].slider_m));
            dF = std::max(dF, std::abs(a.samples[i].force_N - b.samples[i].force_N));
            xMax = std::max(xMax, std::abs(b.samples[i].slider_m));
            FMax = std::max(FMax, std::abs(b.samples[i].force_N));
        }
        qInfo("stuck run, TOL 1e-5: closed form %ld steps, scheme %ld steps (%ld base steps); |dx| %.3g of max|x|, |dF| %.3g of max|F|",
              a.stats.steps, b.stats.steps, b.stats.newtonIterations, dx / xMax, dF / FMax);
        QVERIFY(dx <= 2e-5 * xMax);
        QVERIFY(dF <= 5e-4 * FMax);  // ε_T = 1e6 turns the scheme's x error into F (seen 1.2e-4)
        QVERIFY(a.stats.steps * 3 < b.stats.steps);
    }

    // TR-BDF2's embedded estimate (trbdf2.hpp, TrError) is the local error of the step it
    // comes with: from a sliding state of the Fig. 20 set (ε_T = 1e6), one step h against 256
    // steps h/256 of the same scheme (their own error ~h³/65 536), for h = T/1000, T/2000,
    // T/4000. The estimate of x agrees with the local error to within a factor 1.5 and both
    // fall as h³ (ratio 8 per halving, ≥ 5 required); the estimate of ẋ likewise within 2.
    void embeddedEstimateIsTheLocalError() {
        const SimParams p = lawParams(false, 1);
        const DynamicsModel m = DynamicsModel::fromParams(p);
        const RateStateLaw& law = std::get<RateStateLaw>(m.law);
        const double T = p.drive.period();
        DynState s0 = m.initialState();
        AdaptiveOptions o;
        o.tolerance = 1e-5;
        // A state well inside a slip phase: past the first onset, still sliding.
        QVERIFY(advanceAdaptive(m, s0, 0.1 * T, o).status == RunStatus::Ok);
        QVERIFY(!s0.stuck);
        auto step = [&](const DynState& s, double h, int n, detail::TrError* err) {
            DynState y = s;
            const detail::TrBdf2Constants K(m.rig, law.epsT(), h / n);
            auto prep = law.prepare(K.returnStiffness, K.d, K.tN);
            int its = 0;
            const char* why = nullptr;
            double bad = 0;
            for (int i = 0; i < n; ++i) {
                const double t = y.t;
                const bool ok = detail::trBdf2Step(K, law, prep, m.stage, m.stage.displacement(t + detail::kTrGamma * h / n),
                                                   m.stage.displacement(t + h / n), y, its, why, bad, err);
                if (!ok || y.stuck) return DynState{};
            }
            return y;
        };
        std::vector<double> ex, vx;
        for (double n : {1000.0, 2000.0, 4000.0}) {
            const double h = T / n;
            detail::TrError err;
            const DynState y = step(s0, h, 1, &err), ref = step(s0, h, 256, nullptr);
            QVERIFY(y.t > s0.t && ref.t > s0.t);
            const double eX = ref.x - y.x, eV = ref.v - y.v;
            qInfo("h = T/%.0f: local error x %.3e (estimate %.3e), v %.3e (estimate %.3e)", n, eX, err.x, eV, err.v);
            QVERIFY2(err.x / eX >= 1 / 1.5 && err.x / eX <= 1.5, qPrintable(QString("x: %1 vs %2").arg(err.x).arg(eX)));
            QVERIFY2(err.v / eV >= 0.5 && err.v / eV <= 2.0, qPrintable(QString("v: %1 vs %2").arg(err.v).arg(eV)));
            ex.push_back(std::abs(eX));
            vx.push_back(std::abs(err.x));
        }
        for (size_t i = 1; i < ex.size(); ++i) QVERIFY(ex[i - 1] / ex[i] >= 5 && vx[i - 1] / vx[i] >= 5);
    }

    // The shared Illinois root (illinois.hpp): converges to the root from either sign
    // convention, keeps the point it returns on lo's side, and stops at the bracket width asked.
    void illinoisRoot() {
        const double root = std::acos(0.5);
        int calls = 0;
        auto down = [&](double t) { ++calls; return std::cos(t) - 0.5; };  // > 0 left of the root
        const double a = detail::illinois(down, 0.0, down(0.0), 2.0, down(2.0), 1e-12, true);
        QVERIFY(std::abs(a - root) <= 1e-11);
        QVERIFY(down(a) > 0.0);
        QVERIFY2(calls < 30, qPrintable(QString("%1 evaluations").arg(calls)));
        auto up = [](double t) { return 0.5 - std::cos(t); };  // <= 0 left of the root
        const double b = detail::illinois(up, 0.0, up(0.0), 2.0, up(2.0), 1e-12, false);
        QVERIFY(std::abs(b - root) <= 1e-11);
        QVERIFY(up(b) <= 0.0);
        const double c = detail::illinois(up, 0.0, up(0.0), 2.0, up(2.0), 1e-3, false);
        QVERIFY(c <= root && root - c <= 1e-3 + 1e-12);
    }

    void optionsValidate() {
        AdaptiveOptions o;
        QVERIFY(o.validate().empty());
        o.tolerance = 1e-6;  // below the supported range (grazing stops, adaptive.cpp)
        o.maxStep_s = -1;
        o.minStep_s = NAN;
        o.maxSteps = 0;
        const ParamIssues is = o.validate();
        QCOMPARE(is.size(), size_t(4));
        const RunResult r = simulateAdaptive(fig20Params(), o);
        QVERIFY(r.status == RunStatus::Failed);
        QVERIFY(contains(r.message, "tolerance"));
        SimParams bad = fig20Params();
        bad.rig.mass_kg = -1;
        QVERIFY(simulateAdaptive(bad, AdaptiveOptions{}).status == RunStatus::Failed);
    }

    void budgetAndCancelAreStatuses() {
        AdaptiveOptions o;
        o.maxSteps = 10;
        const RunResult r = simulateAdaptive(fig20Params(), o);
        QVERIFY(r.status == RunStatus::Failed);
        QVERIFY(contains(r.message, "max_steps"));
        std::atomic<bool> cancel{true};
        RunControl ctl;
        ctl.cancel = &cancel;
        const RunResult c = simulateAdaptive(fig20Params(), AdaptiveOptions{}, ctl);
        QVERIFY(c.status == RunStatus::Cancelled);
    }

    // Dense output reproduces the ends and a cubic exactly (Hermite interpolation in x).
    void denseStateInterpolates() {
        const DynamicsModel m = DynamicsModel::fromParams(fig20Params());
        auto cubic = [](double t) { return 1 + 2 * t - 3 * t * t + 0.5 * t * t * t; };
        auto dcubic = [](double t) { return 2 - 6 * t + 1.5 * t * t; };
        DynState a, b;
        a.t = 0.1; a.x = cubic(0.1); a.v = dcubic(0.1); a.law.force_N = 1;
        b.t = 0.4; b.x = cubic(0.4); b.v = dcubic(0.4); b.law.force_N = 2; b.stuck = false;
        for (double t : {0.1, 0.2, 0.33, 0.4}) QVERIFY(std::abs(denseState(m, a, b, t).x - cubic(t)) < 1e-14);
        QCOMPARE(denseState(m, a, b, 0.25).law.force_N, 1.5);
        QCOMPARE(denseState(m, a, b, 0.25).stuck, false);
        QCOMPARE(denseState(m, a, b, 0.25).u, m.stage.displacement(0.25));
    }
};

QTEST_GUILESS_MAIN(TstAdaptiveParts)
#include "tst_adaptive_parts.moc"
