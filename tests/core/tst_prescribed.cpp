// Verification of the prescribed-slip set-up (paper Fig. 15a): the Coulomb step-like trace, the
// agreement of the two integration paths, and the k → huge / m → tiny limits of the dynamics.
#include <QtTest>

#include <cmath>
#include <numbers>

#include "core/integrate/dynamics.hpp"
#include "core/integrate/prescribed.hpp"
#include "core/integrate/simulate.hpp"
#include "physics_helpers.hpp"

using namespace stickslip;
using namespace stickslip::testing;

class TstPrescribed : public QObject {
    Q_OBJECT
private slots:
    // Harmonic slip g = A sin ωt with Coulomb friction: ideal elasto-plastic, so F = ±μ t_N
    // while slipping, with the sign of V; after each reversal of g the contact sticks while the
    // ε_T spring unloads and reloads through 2 μ t_N, i.e. for a slip change 2μt_N/ε_T:
    //   stick time per reversal t_s = arccos(1 − 2μt_N/(ε_T A)) / ω,
    // and during it F = ±μ t_N ∓ ε_T (A − |g|) (linear in g). The trace is a step.
    void coulombStepTrace() {
        SimParams p = fig20Params();
        p.setup = SetupKind::Prescribed;
        p.law = LawKind::Coulomb;
        p.lawParams<CoulombParams>().epsT_N_per_m = 2e4;  // a visible stick window: 2μt_N/ε_T = 0.155 A
        p.integration.outputInterval_s = p.drive.period() / 1000;
        p.cycles = 4;
        const RunResult r = simulate(p);
        QVERIFY2(r.ok(), r.message.c_str());
        QCOMPARE(r.samples.size(), size_t(4 * 1000 + 1));
        const double muTN = p.lawParams<CoulombParams>().mu * p.rig.normalForce_N, A = p.drive.amplitude_m, eps = p.lawParams<CoulombParams>().epsT_N_per_m;
        const double w = p.drive.omega();
        std::vector<long> stickRuns;  // lengths (in samples) of the stick windows after the first reversal
        long run = 0;
        double maxStickErr = 0;
        for (const Sample& s : r.samples) {
            QVERIFY(std::abs(s.stage_m - A * std::sin(w * s.t_s)) < 1e-12);  // g as prescribed
            QCOMPARE(s.slider_m, 0.0);                                        // slider held
            if (!s.stuck) {
                QVERIFY(std::abs(std::abs(s.force_N) - muTN) < 1e-12 * muTN);
                QVERIFY(s.force_N * s.relVel_mps > 0);
                QVERIFY(std::abs(std::abs(s.ratio) - p.lawParams<CoulombParams>().mu) < 1e-12);
            } else {
                QVERIFY(std::abs(s.force_N) <= muTN * (1 + 1e-12));
                QCOMPARE(s.slipRate_mps, 0.0);
            }
            if (s.t_s > 0.25 * p.drive.period()) {  // after the first reversal of g
                if (s.stuck) {
                    ++run;
                    // Unloading from the last extreme ±A: F = ±(μ t_N − ε_T (A − |g|)).
                    const double sg = s.stage_m > 0 ? 1.0 : -1.0;
                    const double expected = sg * (muTN - eps * (A - std::abs(s.stage_m)));
                    maxStickErr = std::max(maxStickErr, std::abs(s.force_N - expected));
                } else if (run > 0) {
                    stickRuns.push_back(run);
                    run = 0;
                }
            }
        }
        const double ts = std::acos(1 - 2 * muTN / (eps * A)) / w;
        const double tsSamples = ts / p.integration.outputInterval_s;
        qInfo("%zu stick windows, closed form %.2f samples each; max stick-branch error %.3g N", stickRuns.size(),
              tsSamples, maxStickErr);
        // One window per reversal of g: at T/4, 3T/4, …, 15T/4.
        QCOMPARE(stickRuns.size(), size_t(8));
        // Each as long as the closed form, ±1 output sample (where the window's ends fall).
        for (long len : stickRuns) QVERIFY2(std::abs(len - tsSamples) <= 1.0, qPrintable(QString::number(len)));
        // The extreme of g is met at a step, not exactly: A − max g ≤ A (ω dt)²/2 = 2e-10 m,
        // i.e. ε_T·that = 4e-6 N.
        QVERIFY(maxStickErr < 1e-5);
    }

    // The two paths agree: the slip history g = u − x of a dynamics run, fed step by step to
    // simulatePrescribed on the same time grid, reproduces the run's friction force. Both feed
    // the law the same Δg and Δt; the differences are the slider solve's tolerance (x to ~1e-13
    // relative, 1e-16 m, i.e. 1e-10 N through ε_T), the local solve's (residual 1e-13 (|F_tr| +
    // t_N)) and round-off in g = u − x (1e-19 m). In slip the viscous return contracts such
    // differences, in stick they add up without growth. We allow 1e-8 μ t_N (seen: ~7e-13 N).
    void pathsAgree_data() {
        QTest::addColumn<bool>("coulomb");
        QTest::addColumn<double>("amplitude");
        QTest::addRow("rate-state A=1mm") << false << 1e-3;
        QTest::addRow("rate-state A=0.4mm") << false << 0.4e-3;
        QTest::addRow("coulomb A=1mm") << true << 1e-3;
    }
    void pathsAgree() {
        QFETCH(bool, coulomb);
        QFETCH(double, amplitude);
        SimParams p = fig20Params();
        p.law = coulomb ? LawKind::Coulomb : LawKind::RateState;
        p.drive.amplitude_m = amplitude;
        const DynamicsModel m = DynamicsModel::fromParams(p);
        DynState s = m.initialState();
        const RunResult dyn = simulateDynamics(m, s, 5 * 10000, 1, true);
        QVERIFY2(dyn.ok(), dyn.message.c_str());
        std::vector<double> t, g;
        for (const Sample& x : dyn.samples) {
            t.push_back(x.t_s);
            g.push_back(x.stage_m - x.slider_m);
        }
        const RunResult pre = simulatePrescribed(m.law, p.rig.normalForce_N, SlipHistory::fromSlip(t, g), 1);
        QVERIFY2(pre.ok(), pre.message.c_str());
        QCOMPARE(pre.samples.size(), dyn.samples.size());
        double errF = 0, errAlpha = 0;
        long slipping = 0, stuckMismatch = 0;
        for (size_t i = 0; i < dyn.samples.size(); ++i) {
            errF = std::max(errF, std::abs(pre.samples[i].force_N - dyn.samples[i].force_N));
            errAlpha = std::max(errAlpha, std::abs(pre.samples[i].alpha - dyn.samples[i].alpha));
            slipping += dyn.samples[i].stuck ? 0 : 1;
            stuckMismatch += pre.samples[i].stuck != dyn.samples[i].stuck ? 1 : 0;
        }
        const double muTN = 0.25 * p.rig.normalForce_N;
        qInfo("max|F_pre - F_dyn| = %.3g N, max|d alpha| = %.3g, %ld slipping steps, %ld stick flags differ", errF,
              errAlpha, slipping, stuckMismatch);
        QVERIFY(slipping > 1000);
        QVERIFY(errF < 1e-8 * muTN);
        QVERIFY(errAlpha < 1e-8);
        // Stick/slip flags may differ only where Φ_trial is at round-off distance from 0.
        QVERIFY(stuckMismatch <= 5);
    }

    // k → huge: the slider cannot move (x ≈ F/k ≈ 1e-12 m), so the dynamics run is the block with
    // the stage displacement as slip, i.e. the prescribed harmonic slip on the same time grid.
    // The slip differs by x, hence the force by ε_T |x| ≤ ε_T μ t_N / k ≈ 2e-6 N at k = 1e12 N/m;
    // we allow 1e-5 N.
    void stiffSpringIsPrescribedSlip() {
        SimParams p = fig20Params();
        p.rig.stiffness_N_per_m = 1e12;
        p.cycles = 3;
        const RunResult dyn = simulate(p);
        QVERIFY2(dyn.ok(), dyn.message.c_str());
        const SlipHistory h = SlipHistory::harmonic(p.drive, p.cycles, p.integration.dt_s);
        const RunResult pre = simulatePrescribed(makeLaw(p), p.rig.normalForce_N, h, 1);
        QVERIFY2(pre.ok(), pre.message.c_str());
        const size_t every = size_t(p.integration.outputEvery());
        QCOMPARE(dyn.samples.size(), pre.samples.size() / every + 1);
        double errF = 0, maxX = 0;
        for (size_t i = 0; i < dyn.samples.size(); ++i) {
            const Sample& q = pre.samples[i * every];
            QVERIFY(std::abs(dyn.samples[i].t_s - q.t_s) < 1e-9);
            errF = std::max(errF, std::abs(dyn.samples[i].force_N - q.force_N));
            maxX = std::max(maxX, std::abs(dyn.samples[i].slider_m));
        }
        qInfo("k = 1e12: max|x| = %.3g m, max|F_dyn - F_pre| = %.3g N", maxX, errF);
        QVERIFY(maxX < 1e-11);
        QVERIFY(errF < 1e-5);
    }

    // The output interval is a view, not a model change: simulate() in the prescribed set-up
    // must give the same F(t) (at common times) whether it records every step or every 100th.
    // The law is integrated with steps ≤ dt either way; a faithful integration of the same
    // g = A sin ωt differs only by round-off and the local solve's tolerance (≤ 1e-6 N here).
    void outputIntervalDoesNotChangePrescribedRun() {
        SimParams p = fig20Params();
        p.setup = SetupKind::Prescribed;
        p.cycles = 3;
        SimParams fine = p;
        fine.integration.outputInterval_s = fine.integration.dt_s;
        const RunResult a = simulate(p), b = simulate(fine);
        QVERIFY(a.ok() && b.ok());
        const size_t every = size_t(p.integration.outputEvery());
        QCOMPARE(a.samples.size(), (b.samples.size() - 1) / every + 1);
        double errF = 0;
        for (size_t i = 0; i < a.samples.size(); ++i)
            errF = std::max(errF, std::abs(a.samples[i].force_N - b.samples[i * every].force_N));
        qInfo("output every T/100 vs every step: max|dF| = %.3g N", errF);
        QVERIFY(errF < 1e-6);
    }

    // m → tiny with no spring (k = 0, c = 0): the force needed to carry the slider, m ü, is
    // negligible, so it never slips and rides on the stage up to the pre-slip x − u = −F/ε_T.
    // Starting at rest on a moving stage (relative velocity Aω) excites the stuck mode
    // sqrt(ε_T/m); undamped, its force amplitude is A ω sqrt(ε_T m) (energy ½ m (Aω)² into the
    // ε_T spring; the trapezoidal rule conserves that quadratic energy), plus the forced m A ω².
    void tinyMassRidesOnStage() {
        SimParams p = fig20Params();
        p.rig.mass_kg = 1e-6;
        p.rig.stiffness_N_per_m = 0;
        p.rig.damping_Ns_per_m = 0;
        const DynamicsModel m = DynamicsModel::fromParams(p);
        DynState s = m.initialState();
        const double A = p.drive.amplitude_m, w = p.drive.omega(), eps = p.lawParams<RateStateParams>().epsT_N_per_m;
        const double bound = A * w * std::sqrt(eps * p.rig.mass_kg) + p.rig.mass_kg * A * w * w;
        long stuck = 0;
        double maxF = 0, maxPreslipErr = 0, maxRel = 0;
        const StepReport rep = advance(m, s, 5 * 10000, [&](const DynState& st) {
            stuck += st.stuck ? 1 : 0;
            maxF = std::max(maxF, std::abs(st.law.force_N));
            maxPreslipErr = std::max(maxPreslipErr, std::abs((st.x - st.u) + st.law.force_N / eps));
            maxRel = std::max(maxRel, std::abs(st.x - st.u));
        });
        QVERIFY2(rep.status == RunStatus::Ok, rep.message.c_str());
        qInfo("m = 1e-6 kg: %ld/50000 stuck, max|F| = %.4g N (bound %.4g), max|x - u| = %.3g m", stuck, maxF, bound, maxRel);
        QCOMPARE(stuck, 50000L);
        QVERIFY(maxF <= bound * (1 + 1e-3));
        QVERIFY(maxF < 0.05 * 0.25 * p.rig.normalForce_N);  // far from the slip limit
        QVERIFY(maxPreslipErr < 1e-15 + 1e-9 * maxRel);
        QVERIFY(maxRel <= bound / eps * (1 + 1e-3));
    }

    // SlipHistory constructors and checks.
    void slipHistory() {
        const SlipHistory v = SlipHistory::fromVelocity({0.0, 1.0, 2.0, 4.0}, {1.0, 3.0, 3.0, -1.0}, 0.5);
        QCOMPARE(v.slip_m.size(), size_t(4));
        QCOMPARE(v.slip_m[1], 0.5 + 2.0);     // trapezoid (1+3)/2·1
        QCOMPARE(v.slip_m[2], 0.5 + 2.0 + 3.0);
        QCOMPARE(v.slip_m[3], 0.5 + 5.0 + 2.0);  // (3−1)/2·2
        QVERIFY(v.validate().empty());
        DriveParams d;
        d.amplitude_m = 2e-3;
        const SlipHistory h = SlipHistory::harmonic(d, 2, d.period() / 100);
        QCOMPARE(h.t_s.size(), size_t(201));
        QVERIFY(std::abs(h.slip_m[25] - 2e-3) < 1e-15);  // quarter period
        QVERIFY(std::abs(h.velocity_mps[0] - 2e-3 * d.omega()) < 1e-15);
        QVERIFY(formatIssues(SlipHistory::fromSlip({0.0, 1.0, 1.0}, {0, 0, 0}).validate()).find("time does not increase") != std::string::npos);
        QVERIFY(!SlipHistory::fromSlip({0.0}, {0}).validate().empty());
        QVERIFY(!SlipHistory::fromSlip({0.0, 1.0}, {0}).validate().empty());
        QVERIFY(formatIssues(SlipHistory::fromSlip({0.0, 1.0}, {0, std::nan("")}).validate()).find("non-finite") != std::string::npos);
        SlipHistory n = SlipHistory::fromSlip({0.0, 1.0}, {0, 1e-3});
        n.normalForce_N = {6.2, -1.0};
        QVERIFY(formatIssues(n.validate()).find("normal force") != std::string::npos);
        // A bad history or t_N is a Failed run with the reason, not a crash.
        const RunResult r = simulatePrescribed(CoulombLaw{CoulombParams{}}, 6.2, SlipHistory::fromSlip({0.0, 0.0}, {0, 0}), 1);
        QVERIFY(r.status == RunStatus::Failed && contains(r.message, "time does not increase"));
        const RunResult r2 = simulatePrescribed(CoulombLaw{CoulombParams{}}, -1.0, v, 1);
        QVERIFY(r2.status == RunStatus::Failed && contains(r2.message, "tN"));
    }

    // A per-sample normal force scales the Coulomb slip force: F = ±μ t_N(t).
    void varyingNormalForce() {
        std::vector<double> t, g, tN;
        for (int i = 0; i <= 100; ++i) {
            t.push_back(i * 1e-3);
            g.push_back(i * 1e-4);  // steady slip at 0.1 m/s
            tN.push_back(5.0 + 0.02 * i);
        }
        SlipHistory h = SlipHistory::fromSlip(t, g);
        h.normalForce_N = tN;
        const RunResult r = simulatePrescribed(CoulombLaw{CoulombParams{}}, 1.0, h, 4);
        QVERIFY2(r.ok(), r.message.c_str());
        for (size_t i = 5; i < r.samples.size(); ++i) {
            QVERIFY(std::abs(r.samples[i].force_N - 0.25 * tN[i]) < 1e-12);
            QVERIFY(std::abs(r.samples[i].ratio - 0.25) < 1e-12);
        }
        // A non-converging law (D_c = 0 bypassing validation) ends with Failed naming step and t.
        RateStateParams bad;
        bad.Dc_m = 0.0;
        const RunResult f = simulatePrescribed(RateStateLaw{bad}, 6.2, h, 1);
        QVERIFY(f.status == RunStatus::Failed);
        QVERIFY2(contains(f.message, "step ") && contains(f.message, "t = "), f.message.c_str());
        QVERIFY(allFinite(f.samples));
    }
};

QTEST_GUILESS_MAIN(TstPrescribed)
#include "tst_prescribed.moc"
