// The adaptive integrator (core/integrate/adaptive.hpp, issue 15) as a whole: order under
// refinement, error against tolerance, located stick–slip switches, output on the requested grid,
// the Coulomb stick threshold, the energy balance, random parameter sets. Its parts (closed-form
// stick, embedded estimate, Illinois root, dense output, options, statuses): tst_adaptive_parts.cpp.
#include <QtTest>

#include <cmath>
#include <random>
#include <vector>

#include "core/analysis/stick_threshold.hpp"
#include "core/integrate/adaptive.hpp"
#include "physics_helpers.hpp"

using namespace stickslip;
using namespace stickslip::testing;

namespace {

// Fixed-step reference: the paper's scheme at 400 000 steps per cycle (the reference),
// sampled at T/100. Its own error is below 1e-5 of the amplitude (first order from 9.7e-4 at
// 7 200 steps per cycle).
std::vector<double> sliderTrace(const RunResult& r) {
    std::vector<double> x;
    for (const Sample& s : r.samples) x.push_back(s.slider_m);
    return x;
}

std::vector<double> referenceTrace(SimParams p) {
    p.integration.dt_s = p.drive.period() / 400000.0;
    return sliderTrace(simulateDynamics(p));
}

// For the rate-state law the fixed step is first order (its error at T/400 000 is ~1e-5, the
// size of the errors TR-BDF2 reaches at T/4000), so its reference is extrapolated:
// 2 x(T/800 000) − x(T/400 000) removes the h term (floor ~1e-6 relative, measured against
// TR-BDF2 itself at T/8000).
std::vector<double> extrapolatedReference(SimParams p) {
    const std::vector<double> coarse = referenceTrace(p);
    p.integration.dt_s = p.drive.period() / 800000.0;
    const RunResult r = simulateDynamics(p);
    std::vector<double> x;
    for (size_t i = 0; i < r.samples.size() && i < coarse.size(); ++i) x.push_back(2.0 * r.samples[i].slider_m - coarse[i]);
    return x;
}

// max |x − x_ref| / max(max |x_ref|, floor) over the samples; NaN when the run failed or the
// grids differ.
double relativeError(const RunResult& r, const std::vector<double>& ref, double floor = 0.0) {
    if (!r.ok() || r.samples.size() != ref.size()) return NAN;
    double e = 0, amp = floor;
    for (size_t i = 0; i < ref.size(); ++i) {
        e = std::max(e, std::abs(r.samples[i].slider_m - ref[i]));
        amp = std::max(amp, std::abs(ref[i]));
    }
    return e / amp;
}

// Least-squares slope of log(err) against log(1/n).
double slope(const std::vector<double>& n, const std::vector<double>& err) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double m = static_cast<double>(n.size());
    for (size_t i = 0; i < n.size(); ++i) {
        const double lx = std::log(1.0 / n[i]), ly = std::log(err[i]);
        sx += lx; sy += ly; sxx += lx * lx; sxy += lx * ly;
    }
    return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

// Times of the stick -> slip and slip -> stick switches of the fixed-step scheme from rest.
std::vector<double> fixedSwitchTimes(const SimParams& p, double tEnd, double dt) {
    DynamicsModel m = DynamicsModel::fromParams(p);
    m.dt_s = dt;
    DynState s = m.initialState();
    std::vector<double> out;
    bool stuck = true;
    advance(m, s, std::lround(tEnd / dt), [&](const DynState& st) {
        if (st.stuck != stuck) out.push_back(st.t - dt);  // the switch is inside the step
        stuck = st.stuck;
    });
    return out;
}

}  // namespace

class TstAdaptive : public QObject {
    Q_OBJECT
private slots:
    // Order under refinement of the extrapolated step itself: the step size held at h_max
    // (tolerance 0.5 never rejects; after a slip onset the steps grow back from h_max/64) over
    // 5 cycles. Coulomb (Newmark + extrapolation, the law exact in closed form, switches
    // located): h_max = T/1000 … T/8000 against the fixed step at T/400 000, slope ≥ 1.8 (seen
    // 2.05). Rate-state by TR-BDF2 (trbdf2.hpp) + extrapolation: T/1000 … T/4000 against the
    // extrapolated reference (beyond, its floor of ~1e-6), slope ≥ 2 (seen 2.99: the kept value
    // (4y₂ − y₁)/3 of a second-order step; 2.29 with AdaptiveOptions::embeddedSlip).
    // Rate-state by the paper's step (trBdf2 off), for comparison: order reduction where h
    // approaches η t_N/ε_T ≈ 4 µs, slope ≥ 1.1 (seen 1.37).
    void observedOrder_data() {
        QTest::addColumn<bool>("coulomb");
        QTest::addColumn<bool>("trBdf2");
        QTest::addColumn<double>("minOrder");
        QTest::addRow("coulomb") << true << true << 1.8;
        QTest::addRow("rate-state, TR-BDF2") << false << true << 2.0;
        QTest::addRow("rate-state, Newmark + backward Euler") << false << false << 1.1;
    }
    void observedOrder() {
        QFETCH(bool, coulomb);
        QFETCH(bool, trBdf2);
        QFETCH(double, minOrder);
        // The scheme's own order: its stuck steps too (the closed-form ones are exact, and would
        // leave only the slip phases to refine, whose error then meets the reference's floor).
        const SimParams p = lawParams(coulomb, 5);
        const std::vector<double> ref = coulomb ? referenceTrace(p) : extrapolatedReference(p);
        std::vector<double> ns = {1000, 2000, 4000, 8000}, err;
        if (!coulomb && trBdf2) ns.pop_back();
        for (double n : ns) {
            AdaptiveOptions o;
            o.tolerance = 0.5;  // the largest allowed: never rejects here
            o.trBdf2 = trBdf2;
            o.closedFormStick = false;
            o.maxStep_s = p.drive.period() / n;
            const RunResult r = simulateAdaptive(p, o);
            QVERIFY2(r.ok(), r.message.c_str());
            err.push_back(relativeError(r, ref));
            qInfo("%s: h = T/%.0f: %ld steps, error %.3e", coulomb ? "coulomb" : "rate-state", n, r.stats.steps, err.back());
        }
        for (size_t i = 1; i < err.size(); ++i) QVERIFY(err[i] < err[i - 1]);
        const double order = slope(ns, err);
        qInfo("observed order %.2f", order);
        QVERIFY2(order >= minOrder, qPrintable(QString("order %1").arg(order)));
    }

    // Error against tolerance over 20 cycles (the measure; A = 1 mm, ε_T = 1e6, the
    // paper's second set A = 0.4 mm, ε_T = 1.1e4, and the app's Fig. 20 preset A = 1 mm,
    // ε_T = 1.1e4, whose slider rings while it slides): monotone in the tolerance and within 2× of
    // it from above (error ≤ 2 TOL); from below only ≥ TOL/50. Rate-state runs are measured
    // against the extrapolated reference (the plain T/400 000 one is itself ~1e-5 off).
    // Seen (TOL 1e-2 … 1e-5, session 26, slip steps judged by the kept value's estimate): Coulomb
    // 1 mm 0.43 0.59 0.70 0.73; Coulomb 0.4 mm 0.39 0.43 0.52 0.59; Coulomb preset 0.33 0.41 0.41
    // 0.39; rate-state (TR-BDF2) 1 mm 0.12 0.18 0.22 0.22; rate-state 0.4 mm 0.23 0.22 0.24 0.32;
    // rate-state preset 0.22 0.24 0.27 0.74 (with y₂'s estimate and the slip credit of sessions
    // 24–25, 4: 1.47 1.55 2.91, failing).
    void errorFollowsTolerance_data() {
        QTest::addColumn<bool>("coulomb");
        QTest::addColumn<double>("amplitude");
        QTest::addColumn<double>("epsT");
        QTest::addColumn<double>("smallestTol");
        QTest::addRow("coulomb A=1mm eps=1e6") << true << 1e-3 << 1e6 << 1e-5;
        QTest::addRow("rate-state A=1mm eps=1e6") << false << 1e-3 << 1e6 << 1e-5;
        QTest::addRow("coulomb A=0.4mm eps=1.1e4") << true << 0.4e-3 << 1.1e4 << 1e-5;
        QTest::addRow("rate-state A=0.4mm eps=1.1e4") << false << 0.4e-3 << 1.1e4 << 1e-5;
        QTest::addRow("coulomb A=1mm eps=1.1e4") << true << 1e-3 << 1.1e4 << 1e-5;
        QTest::addRow("rate-state A=1mm eps=1.1e4") << false << 1e-3 << 1.1e4 << 1e-5;
    }
    void errorFollowsTolerance() {
        QFETCH(bool, coulomb);
        QFETCH(double, amplitude);
        QFETCH(double, epsT);
        QFETCH(double, smallestTol);
        SimParams p = lawParams(coulomb, 20);
        p.drive.amplitude_m = amplitude;
        p.lawParams<RateStateParams>().epsT_N_per_m = p.lawParams<CoulombParams>().epsT_N_per_m = epsT;
        const std::vector<double> ref = coulomb ? referenceTrace(p) : extrapolatedReference(p);
        double prev = INFINITY;
        for (double tol : {1e-2, 1e-3, 1e-4, 1e-5}) {
            if (tol < smallestTol) break;
            AdaptiveOptions o;
            o.tolerance = tol;
            const RunResult r = simulateAdaptive(p, o);
            QVERIFY2(r.ok(), r.message.c_str());
            const double e = relativeError(r, ref);
            qInfo("tol %.0e: %ld steps (%ld base steps), error %.3e = %.2f tol", tol, r.stats.steps,
                  r.stats.newtonIterations, e, e / tol);
            QVERIFY2(e <= 2 * tol, qPrintable(QString("error %1 at tolerance %2").arg(e).arg(tol)));
            QVERIFY2(e >= 0.02 * tol, qPrintable(QString("error %1 at tolerance %2").arg(e).arg(tol)));
            QVERIFY(e < prev);
            prev = e;
        }
    }

    // Switch location. (1) The slip onset from rest (~82 µs) agrees with the fixed-step scheme at
    // dt = 1e-8 s (switch known to within its step) to 3 of its steps plus 1e-8 s; a scheme that
    // does not cut steps at the switch misses it by a fraction of its step (~1e-5 s here).
    // (2) The first stop (~7.5 ms Coulomb, ~8.4 ms rate-state) is ill-conditioned for the
    // fixed-step scheme (dt = 4e-8, 1e-8, 2.5e-9 s put it at 7.51096, 7.51072, 7.50482 ms,
    // measured), so there the located times at TOL 1e-5 and 2e-5 must agree with each other and
    // with the fixed-step range to 1e-5 s (seen: 7.510998 / 7.510997 ms Coulomb, 8.425544 /
    // 8.430281 ms rate-state, which converges to ~8.4293 ms at tighter tolerances). Weak for
    // rate-state: the viscoplastic stop is where Φ → 0, not located as sharply as Coulomb's.
    void switchesLocated_data() {
        QTest::addColumn<bool>("coulomb");
        QTest::addRow("coulomb") << true;
        QTest::addRow("rate-state") << false;
    }
    void switchesLocated() {
        QFETCH(bool, coulomb);
        const SimParams p = lawParams(coulomb, 1);
        const double tEnd = 0.02, dtRef = 1e-8;
        const std::vector<double> ref = fixedSwitchTimes(p, tEnd, dtRef);
        QVERIFY(ref.size() >= 2);
        const DynamicsModel m = DynamicsModel::fromParams(p);
        std::vector<std::vector<double>> got;
        for (double tol : {1e-5, 2e-5}) {
            DynState s = m.initialState();
            AdaptiveOptions o;
            o.tolerance = tol;
            // A located switch ends one step (flag of the old regime) and starts the next (new one).
            std::vector<double> t;
            bool stuck = true;
            const AdaptiveReport rep = advanceAdaptive(m, s, tEnd, o, [&](const DynState& a, const DynState& b) {
                if (b.stuck != stuck) t.push_back(a.t);
                stuck = b.stuck;
            });
            QVERIFY2(rep.status == RunStatus::Ok, rep.message.c_str());
            QVERIFY(rep.switches >= 2);
            QVERIFY(t.size() >= 2);
            qInfo("tol %.0e: onset %.9f s (fixed dt=1e-8: %.9f s), first stop %.9f s", tol, t[0], ref[0], t[1]);
            got.push_back(t);
        }
        QVERIFY2(std::abs(got[0][0] - ref[0]) <= 3 * dtRef + 1e-8, qPrintable(QString("onset %1 s, reference %2 s")
                                                                               .arg(got[0][0], 0, 'g', 10).arg(ref[0], 0, 'g', 10)));
        QVERIFY(std::abs(got[1][0] - ref[0]) <= 3 * dtRef + 1e-8);
        QVERIFY(std::abs(got[0][1] - ref[1]) <= 1e-5);
        QVERIFY2(std::abs(got[0][1] - got[1][1]) <= 1e-5, qPrintable(QString("first stop %1 s vs %2 s")
                                                                         .arg(got[0][1], 0, 'g', 10).arg(got[1][1], 0, 'g', 10)));
    }

    // A run whose last step holds a switch: the step is cut at the switch, and the run goes on
    // to tEnd in a further step instead of labelling the switch's state with tEnd (bug found in
    // session 14: the state at the onset was returned as the state at tEnd). Checked as the
    // chain of accepted steps: contiguous, ending at tEnd, the stage displacement of the end
    // state at tEnd's, and slipping.
    void lastStepWithASwitchReachesTheEnd_data() { switchesLocated_data(); }
    void lastStepWithASwitchReachesTheEnd() {
        QFETCH(bool, coulomb);
        const DynamicsModel m = DynamicsModel::fromParams(lawParams(coulomb, 1));
        AdaptiveOptions o;
        o.tolerance = 1e-4;
        DynState s = m.initialState();
        double onset = -1;
        advanceAdaptive(m, s, 0.002, o, [&](const DynState& a, const DynState& b) {
            if (!b.stuck && onset < 0) onset = a.t;  // a located switch starts the first slipping step
        });
        QVERIFY(onset > 0);
        const double tEnd = onset + 1e-7;
        s = m.initialState();
        std::vector<std::pair<double, double>> steps;
        const AdaptiveReport rep = advanceAdaptive(m, s, tEnd, o, [&](const DynState& a, const DynState& b) {
            steps.emplace_back(a.t, b.t);
        });
        QVERIFY2(rep.status == RunStatus::Ok, rep.message.c_str());
        QVERIFY(!steps.empty());
        for (size_t i = 1; i < steps.size(); ++i) QCOMPARE(steps[i].first, steps[i - 1].second);
        qInfo("onset %.9g s, tEnd %.9g s, last step ends %.9g s", onset, tEnd, steps.back().second);
        QVERIFY(std::abs(steps.back().second - tEnd) <= 1e-12);
        QCOMPARE(s.t, tEnd);
        QVERIFY(std::abs(s.u - m.stage.displacement(tEnd)) <= 1e-12 * std::abs(m.stage.amplitude()));
        QVERIFY(!s.stuck);  // 0.1 µs after the onset it slips
    }

    // Output on the requested grid (dense output), the once-per-period states at the exact
    // phase t = kT, and the start sample, with transient cycles.
    void outputGridAndPhase() {
        SimParams p = lawParams(false, 3);
        p.transientCycles = 2;
        p.integration.outputInterval_s = p.drive.period() / 50.0;
        AdaptiveOptions o;
        o.tolerance = 1e-4;
        const RunResult r = simulateAdaptive(p, o);
        QVERIFY2(r.ok(), r.message.c_str());
        QCOMPARE(r.samples.size(), size_t(3 * 50 + 1));
        QVERIFY(allFinite(r.samples));
        const double T = p.drive.period();
        for (size_t i = 0; i < r.samples.size(); ++i)
            QVERIFY(std::abs(r.samples[i].t_s - (2 * T + static_cast<double>(i) * T / 50.0)) <= 1e-12 * T * 5);
        QCOMPARE(r.period.samples.size(), size_t(3));
        for (size_t k = 0; k < 3; ++k) QVERIFY(std::abs(r.period.samples[k].t_s - static_cast<double>(k + 3) * T) <= 1e-12 * T * 5);
        // The period states are the grid samples at the same times (both from the dense output).
        for (size_t k = 0; k < 3; ++k) {
            const Sample& g = r.samples[50 * (k + 1)];
            QVERIFY(std::abs(g.slider_m - r.period.samples[k].slider_m) <= 1e-15);
        }
        QVERIFY(r.period.maxRelVel_mps > 0);
    }

    // Coulomb stick threshold (stick_threshold.hpp closed form): started on the stuck forced
    // response, the adaptive run sticks throughout below it and slips above it.
    void coulombStickThreshold_data() {
        QTest::addColumn<double>("fraction");
        QTest::addColumn<bool>("expectStick");
        QTest::addRow("0.95 A_s") << 0.95 << true;
        QTest::addRow("1.05 A_s") << 1.05 << false;
    }
    void coulombStickThreshold() {
        QFETCH(double, fraction);
        QFETCH(bool, expectStick);
        SimParams p = lawParams(true, 10);
        p.rig.damping_Ns_per_m = 0.0;
        const double As = stickThresholdAmplitude(p);
        p.drive.amplitude_m = fraction * As;
        const double w = p.drive.omega(), eps = p.lawParams<CoulombParams>().epsT_N_per_m;
        // Stuck forced response x = X sin ωt, X = ε_T A / (k + ε_T − m ω²) (c = 0).
        const double X = eps * p.drive.amplitude_m / (p.rig.stiffness_N_per_m + eps - p.rig.mass_kg * w * w);
        const DynamicsModel m = DynamicsModel::fromParams(p);
        DynState s = m.initialState();
        s.v = X * w;
        AdaptiveOptions o;
        o.tolerance = 1e-5;
        long slipSteps = 0;
        double maxF = 0;
        const AdaptiveReport rep = advanceAdaptive(m, s, 10 * p.drive.period(), o, [&](const DynState&, const DynState& b) {
            slipSteps += b.stuck ? 0 : 1;
            maxF = std::max(maxF, std::abs(b.law.force_N));
        });
        QVERIFY2(rep.status == RunStatus::Ok, rep.message.c_str());
        const double muTN = p.lawParams<CoulombParams>().mu * p.rig.normalForce_N;
        qInfo("A = %.3f A_s: %ld of %ld steps slipped, max|F| = %.6g N (mu tN %.6g)", fraction, slipSteps, rep.accepted, maxF, muTN);
        if (expectStick) {
            QCOMPARE(slipSteps, 0L);
            QVERIFY(std::abs(maxF / muTN - fraction) < 1e-3);  // |F| amplitude = (A/A_s) μ t_N
        } else {
            QVERIFY(slipSteps > 0);
        }
    }

    // Energy over cycles 5–15 (the sets of tst_energy), with Simpson's rule on the dense output of
    // every accepted step (switches are step ends, so F is smooth inside every step; the closed-
    // form stuck steps span ringing that the trapezoidal rule on their ends does not resolve):
    //   mechanical: ∫F ẋ dt = Δ(½ m ẋ² + ½ k x²) + ∫c ẋ² dt   (Eq. 8 times ẋ), to 1e-4 of the stage
    //               work ∫F u̇ dt (the quadrature and the run's errors are O(h²); seen ≤ 3.4e-5);
    //   contact:    ∫F ġ dt − Δ(F²/2ε_T) is the slip dissipation (Eq. 4 times F): > 0 overall;
    //   stuck steps: no plastic slip p = g − F/ε_T at all (Eq. 4 with λ̇ = 0), so Σ F̄ Δp over
    //               them is ≤ 1e-6 of the slip dissipation (seen 2e-8 … 5e-8 on the four sets,
    //               both schemes: slips far below the tolerance in steps labelled stuck, e.g.
    //               a half step that slips where the located full step does not). The trapezoidal ∫F ġ dt
    //               − Δ(F²/2ε_T) over the same steps, used before, measured the quadrature's O(h³)
    //               error, not slip (seen 5.6e-5 of it with Newmark, 1.1e-4 with TR-BDF2's longer
    //               stuck steps on the ε_T = 1.1e4 set); it is printed.
    // Unlike the fixed-step identity of tst_energy this is not exact for the extrapolated steps,
    // so it checks the accuracy of the adaptive run, not just the algebra.
    void energyBalance_data() {
        QTest::addColumn<bool>("coulomb");
        QTest::addColumn<double>("amplitude");
        QTest::addColumn<double>("epsT");
        QTest::addRow("rate-state A=1mm eps=1e6") << false << 1e-3 << 1e6;
        QTest::addRow("rate-state A=0.4mm eps=1.1e4") << false << 0.4e-3 << 1.1e4;
        QTest::addRow("coulomb A=1mm eps=1e6") << true << 1e-3 << 1e6;
        QTest::addRow("coulomb A=0.4mm eps=1.1e4") << true << 0.4e-3 << 1.1e4;
    }
    void energyBalance() {
        QFETCH(bool, coulomb);
        QFETCH(double, amplitude);
        QFETCH(double, epsT);
        SimParams p = lawParams(coulomb, 10);
        p.drive.amplitude_m = amplitude;
        p.lawParams<RateStateParams>().epsT_N_per_m = p.lawParams<CoulombParams>().epsT_N_per_m = epsT;
        const DynamicsModel m = DynamicsModel::fromParams(p);
        const double T = p.drive.period(), k = p.rig.stiffness_N_per_m, mass = p.rig.mass_kg, c = p.rig.damping_Ns_per_m;
        AdaptiveOptions o;
        o.tolerance = 1e-4;
        DynState s = m.initialState();
        QVERIFY(advanceAdaptive(m, s, 5 * T, o).status == RunStatus::Ok);
        auto mech = [&](const DynState& st) { return 0.5 * mass * st.v * st.v + 0.5 * k * st.x * st.x; };
        const double mech0 = mech(s), F0 = s.law.force_N;
        double work = 0, powerX = 0, damping = 0, contact = 0, stuckDissipation = 0, slipDissipation = 0;
        double stuckPlastic = 0;
        constexpr int kSub = 16;
        auto plastic = [&](const DynState& st) { return st.u - st.x - st.law.force_N / epsT; };
        const AdaptiveReport rep = advanceAdaptive(m, s, 15 * T, o, [&](const DynState& a, const DynState& b) {
            // Composite Simpson on the dense output, kSub panels per step.
            const double h = b.t - a.t;
            double w = 0, px = 0, dmp = 0, fg = 0;
            for (int j = 0; j <= kSub; ++j) {
                const DynState q = denseState(m, a, b, a.t + h * j / kSub);
                const double wt = (j == 0 || j == kSub ? 1.0 : (j % 2 ? 4.0 : 2.0)) * h / (3.0 * kSub);
                const double uv = m.stage.velocity(q.t);
                w += wt * q.law.force_N * uv;
                px += wt * q.law.force_N * q.v;
                dmp += wt * c * q.v * q.v;
                fg += wt * q.law.force_N * (uv - q.v);
            }
            work += w;
            powerX += px;
            damping += dmp;
            const double d = fg - (b.law.force_N * b.law.force_N - a.law.force_N * a.law.force_N) / (2 * epsT);
            contact += d;
            (b.stuck && a.stuck ? stuckDissipation : slipDissipation) += d;
            if (b.stuck && a.stuck) stuckPlastic += 0.5 * (a.law.force_N + b.law.force_N) * (plastic(b) - plastic(a));
        });
        QVERIFY2(rep.status == RunStatus::Ok, rep.message.c_str());
        const double mechResidual = powerX - (mech(s) - mech0) - damping;
        qInfo("W_stage %.9g J: int F xdot %.9g, d(mech) %.3g, damping %.9g, residual %.3g (%.3g of W); slip %.9g J, "
              "in stuck steps %.3g J (quadrature), F dp %.3g J; d(F^2/2eps) %.3g",
              work, powerX, mech(s) - mech0, damping, mechResidual, mechResidual / work, slipDissipation, stuckDissipation,
              stuckPlastic,
              (s.law.force_N * s.law.force_N - F0 * F0) / (2 * epsT));
        QVERIFY(work > 0);
        QVERIFY(slipDissipation > 0);
        QVERIFY2(std::abs(mechResidual) <= 1e-4 * work, qPrintable(QString("mechanical residual %1 of W").arg(mechResidual / work)));
        QVERIFY2(std::abs(stuckPlastic) <= 1e-6 * slipDissipation, qPrintable(QString("plastic work in stuck steps %1 J").arg(stuckPlastic)));
        QVERIFY(std::abs(stuckDissipation) <= 3e-4 * slipDissipation);
        // Bookkeeping: ġ = u̇ − ẋ, so the stage work splits exactly into the two parts.
        const double dElastic = (s.law.force_N * s.law.force_N - F0 * F0) / (2 * epsT);
        QVERIFY(std::abs(work - (contact + dElastic + powerX)) <= 1e-12 * work);
    }

    // Random parameter sets over the app's slider ranges (log-uniform: A 0.1–5 mm, f 1–20 Hz,
    // t_N 0.5–40 N, k 250–18 000 N/m, m* 0.1–2 kg, damping ratio 1e-4–0.05, μ 0.05–0.8,
    // C1 ≤ μ, η 0.01–10 s/m, D_c 1–1000 µm, r 0.1–5, v_c 1e-3–1 m/s, ε_T 1e3–1e8 N/m), one
    // cycle from rest, error relative to max(max|x|, 5 % of A) (the integrator's own scale):
    // every run succeeds; TR-BDF2 at TOL 1e-4 and 1e-3 is within 2 TOL of TOL 1e-5; the paper's
    // step extrapolated (TOL 1e-5) and the fixed step at T/200 000 agree with it to 1e-3.
    // Seen on the 60 sets (session 24): within 3.3e-5 at TOL 1e-4 and 8.5e-4 at 1e-3. Written after this check
    // found three faults on the paper's sets' neighbours (docs/adaptive.md, session 16): α
    // extrapolated to +17.7 in one accepted step, the TR stage's slip rate taken from Φ where
    // the return map held F at 0, and that stage's slip direction at F = 0. C1 > μ lets the
    // strength μ + K1 fall below 0 (the return map then holds F at 0; the fixed step itself
    // does not converge there at T/1.6e6): those sets are only required to run.
    void randomSetsAgreeAcrossTolerances() {
        std::mt19937 rng(1);
        auto lu = [&](double a, double b) {
            return std::exp(std::uniform_real_distribution<double>(std::log(a), std::log(b))(rng));
        };
        double worst4 = 0, worst3 = 0, worstN = 0, worstF = 0;
        int degenerate = 0;
        for (int i = 0; i < 60; ++i) {
            SimParams p = lawParams(false, 1);
            p.drive.amplitude_m = lu(1e-4, 5e-3);
            p.drive.frequency_Hz = lu(1, 20);
            p.rig.normalForce_N = lu(0.5, 40);
            p.rig.stiffness_N_per_m = lu(250, 18000);
            p.rig.mass_kg = lu(0.1, 2);
            p.rig.damping_Ns_per_m = dampingFromRatio(lu(1e-4, 0.05), p.rig.stiffness_N_per_m, p.rig.mass_kg);
            auto& rs = p.lawParams<RateStateParams>();
            rs.mu = lu(0.05, 0.8);
            rs.C1 = lu(0.01, i % 6 == 5 ? 3.0 : 1.0) * rs.mu;  // every sixth may have C1 > μ
            rs.eta_s_per_m = lu(0.01, 10);
            rs.Dc_m = lu(1e-6, 1e-3);
            rs.r = lu(0.1, 5);
            rs.vc_mps = lu(1e-3, 1);
            rs.epsT_N_per_m = lu(1e3, 1e8);
            p.integration.outputInterval_s = p.drive.period() / 100;
            auto run = [&](double tol, bool tr) {
                AdaptiveOptions o;
                o.tolerance = tol;
                o.trBdf2 = tr;
                return simulateAdaptive(p, o);
            };
            const RunResult r5 = run(1e-5, true), r4 = run(1e-4, true), r3 = run(1e-3, true), n5 = run(1e-5, false);
            for (const RunResult* r : {&r5, &r4, &r3, &n5}) QVERIFY2(r->ok() && allFinite(r->samples), r->message.c_str());
            if (rs.C1 > rs.mu) { ++degenerate; continue; }
            SimParams q = p;
            q.integration.dt_s = p.drive.period() / 200000;
            const RunResult f = simulateDynamics(q);
            QVERIFY(f.ok());
            const std::vector<double> ref = sliderTrace(r5);
            auto err = [&](const RunResult& r) { return relativeError(r, ref, 0.05 * p.drive.amplitude_m); };
            const double e4 = err(r4), e3 = err(r3), eN = err(n5), eF = err(f);
            worst4 = std::max(worst4, e4);
            worst3 = std::max(worst3, e3);
            worstN = std::max(worstN, eN);
            worstF = std::max(worstF, eF);
            const QString what = QString("set %1: TOL 1e-4 %2, 1e-3 %3, Newmark %4, fixed %5").arg(i).arg(e4).arg(e3).arg(eN).arg(eF);
            QVERIFY2(e4 <= 2e-4 && e3 <= 2e-3 && eN <= 1e-3 && eF <= 1e-3, qPrintable(what));
        }
        qInfo("60 sets (%d with C1 > mu, run only): worst TOL 1e-4 %.2e, 1e-3 %.2e, Newmark %.2e, fixed T/200000 %.2e",
              degenerate, worst4, worst3, worstN, worstF);
    }
};

QTEST_GUILESS_MAIN(TstAdaptive)
#include "tst_adaptive.moc"
