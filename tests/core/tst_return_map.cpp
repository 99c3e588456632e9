// Verification of the friction laws' return mapping against the paper's closed forms:
// Eq. 5 (steady sliding), Eq. 6 (velocity jump), the consistent tangent, and robustness of the
// local solve over the whole practical range of ε_T and η.
#include <QtTest>

#include <cmath>
#include <random>
#include <vector>

#include "core/friction/friction_law.hpp"
#include "core/friction/slip_newton.hpp"
#include "core/integrate/dynamics.hpp"
#include "core/integrate/prescribed.hpp"
#include "physics_helpers.hpp"

using namespace stickslip;
using namespace stickslip::testing;

namespace {

// Drive the law at constant slip velocity V for `steps` steps of dt, by the return map alone.
LawState slideAt(const RateStateLaw& law, double tN, LawState s, double V, double dt, long steps,
                 ReturnMapResult* last = nullptr) {
    ReturnMapResult r;
    for (long i = 0; i < steps; ++i) {
        r = law.returnMap(s, V * dt, dt, tN);
        s = r.state;
    }
    if (last) *last = r;
    return s;
}

}  // namespace

class TstReturnMap : public QObject {
    Q_OBJECT
private slots:
    // The shared slip solve (slip_newton.hpp) on a residual of the return map's shape,
    // R(x) = a − k x − c (1 − e^{−x/d}), strictly decreasing with R(0) = a > 0: its root to the
    // tolerance from the known start, from warm starts on either side of it (and one outside the
    // bracket, ignored), and through the bisection safeguard when R' is given with the wrong sign
    // (a Newton step out of the bracket).
    void sharedSlipSolveFindsTheRoot() {
        const double a = 5.0, k = 1e3, c = 2.0, d = 1e-3;
        long evals = 0;
        auto eval = [&](double x, double& R, double& dR) {
            ++evals;
            const double e = std::exp(-x / d);
            R = a - k * x - c * (1.0 - e);
            dR = -k - c * e / d;
        };
        const double ftol = 1e-13 * a, hi = a / k;
        double Rhi = 0, dRhi = 0;
        eval(hi, Rhi, dRhi);
        QVERIFY(Rhi < 0.0);
        double R0 = 0, dR0 = 0;
        eval(0.0, R0, dR0);
        for (const double hint : {0.0, 0.3 * hi, 0.9 * hi, 2.0 * hi}) {
            evals = 0;
            const SlipRoot r = solveSlip(eval, 0.0, R0, dR0, 0.0, hi, hint, ftol);
            QVERIFY(r.converged);
            QVERIFY(r.iterations >= 1 && r.iterations <= 12);
            QCOMPARE(long(r.iterations), evals);  // every iteration is one evaluation
            double R = 0, dR = 0;
            eval(r.x, R, dR);
            QVERIFY2(std::abs(R) <= ftol, qPrintable(QString::number(R)));
            QCOMPARE(r.R, R);
            QCOMPARE(r.dR, dR);
        }
        // A slope of the wrong sign at the start sends Newton out of the bracket: bisection.
        const SlipRoot r = solveSlip(eval, 0.0, R0, +1.0, 0.0, hi, 0.0, ftol);
        QVERIFY(r.converged);
        QVERIFY(r.x > 0.0 && r.x < hi);
        double R = 0, dR = 0;
        eval(r.x, R, dR);
        QVERIFY(std::abs(R) <= ftol);
    }
    // expOrZero is std::exp bit for bit (it only skips the library's underflow path where exp
    // rounds to +0), over random arguments and at the edge of the subnormals.
    void expOrZeroIsExp() {
        std::mt19937_64 rng(3);
        std::uniform_real_distribution<double> U(-800.0, 5.0);
        for (int i = 0; i < 100000; ++i) {
            const double y = U(rng);
            QVERIFY2(expOrZero(y) == std::exp(y), qPrintable(QString::number(y, 'g', 17)));  // exact, not QCOMPARE's fuzzy
        }
        for (double y : {-708.4, -744.0, -745.1, -745.13, -745.14, -745.2, -746.0, std::nextafter(-746.0, 0.0), -746.5, -1e4})
            QVERIFY2(expOrZero(y) == std::exp(y) && std::signbit(expOrZero(y)) == std::signbit(std::exp(y)),
                     qPrintable(QString::number(y, 'g', 17)));
        QVERIFY(expOrZero(-746.0) == 0.0);
    }
    // The certificate that lets the return maps skip evaluating R at the zero-force slip a/ε
    // (slip_newton.hpp): whenever it says "certainly negative", R evaluated with the true
    // exponential is negative, over random residuals of the return map's form and lower bounds
    // of α/r anywhere below the true value; it does say so for most of them (else it saves
    // nothing); and in the bare law a step that does slide to zero force (C1 > μ, a fast step,
    // little viscosity: R(a/ε) > 0) still does so, force exactly 0 (the extended law's, in both
    // state steps: tst_effects::stateLowerBoundIsBelowTheStep).
    void zeroForceCheckNeedsNoEvaluationWhenCertain() {
        std::mt19937_64 rng(7);
        std::uniform_real_distribution<double> U(0.0, 1.0);
        long certain = 0, negative = 0;
        for (int i = 0; i < 200000; ++i) {
            const double a = std::pow(10.0, -3.0 + 6.0 * U(rng)), kx = a * 2.0 * U(rng);
            const double y0 = a * (-1.0 + 3.0 * U(rng)), c = a * 3.0 * U(rng);
            const double u = -800.0 + 805.0 * U(rng) * U(rng), uLow = u - (i % 3 == 0 ? 0.0 : 5.0 * U(rng));
            const double R = a - kx - y0 - c * (std::exp(u) - 1.0);
            negative += R < 0.0;
            if (!slipResidualCertainlyNegative(a, kx, y0, c, uLow)) continue;
            ++certain;
            QVERIFY2(R < 0.0, qPrintable(QString("a=%1 kx=%2 y0=%3 c=%4 u=%5 uLow=%6: R=%7")
                                             .arg(a).arg(kx).arg(y0).arg(c).arg(u).arg(uLow).arg(R)));
        }
        qInfo("certain for %ld of %ld negative residuals", certain, negative);
        QVERIFY(certain > negative / 2);
        QVERIFY(!slipResidualCertainlyNegative(1.0, 0.5, 0.0, 1.0, -1.0));   // R ≤ 1.5: not certain
        QVERIFY(!slipResidualCertainlyNegative(1.0, 1.0, -1e-12, 0.0, 0.0));  // R = 1e-12 > 0
        QVERIFY(slipResidualCertainlyNegative(1.0, 1.0, 0.1, 0.2, -0.1));     // R ≤ −0.08
        QVERIFY(!slipResidualCertainlyNegative(1.0, 1.0, 0.1, -0.2, -0.1));   // c < 0: no claim

        RateStateParams p;
        p.mu = 0.05;
        p.C1 = 0.5;
        p.eta_s_per_m = 1e-6;
        const RateStateLaw law{p};
        const double tN = 6.2, dt = 1e-5, dg = 1e-3;  // trial 1000 N, a/ε = 1 mm in 10 µs
        const ReturnMapResult r = law.returnMap(LawState{0.0, 0.0, {}}, dg, dt, tN);
        QCOMPARE(r.state.force_N, 0.0);
        QCOMPARE(r.slipIncrement_m, dg);
        QCOMPARE(r.tangent_N_per_m, 0.0);
        // The usual case the certificate is for: C1 > μ but a slow step, R(a/ε) < 0.
        const ReturnMapResult slow = law.returnMap(LawState{0.0, 0.0, {}}, 1e-6, 1e-3, tN);
        QVERIFY2(slow.converged && !slow.stuck && slow.state.force_N > 0.0 && slow.slipIncrement_m < 1e-6,
                 qPrintable(QString("F=%1 slip=%2 k=%3").arg(slow.state.force_N).arg(slow.slipIncrement_m).arg(slow.tangent_N_per_m)));
    }
    // Eq. 5: in steady sliding Ḟ = 0 and α̇ = 0, so λ̇ = |V|, α = −C2|V| and Φ = η t_N |V|:
    //   |F|/t_N = μ + K1(−C2|V|) + η|V|.
    // Backward Euler has exactly this fixed point (Δλ = VΔt, α(1+Δλ/D_c) = α − C2Δλ²/(D_cΔt)
    // gives α = −C2 Δλ/Δt), so after the transients have decayed the discrete force must match
    // the closed form to the local solver tolerance (1e-13 relative) — 1e-6 relative is ample and
    // still fails for any error in K1, C2, η or the sign conventions.
    // The state relaxes over the slip distance D_c: with Δλ = D_c/10 per step the BE contraction
    // factor is 1/1.1 per step, so 3000 steps leave e^-286 of the initial transient.
    void eq5SteadySliding_data() {
        QTest::addColumn<double>("V");
        QTest::addColumn<double>("eta");
        QTest::addColumn<double>("vc");
        for (double V : {1e-4, 1e-3, 1e-2, 0.05, 0.1, 0.3, -0.02})
            QTest::addRow("V=%g eta=0.6 vc=0.1", V) << V << 0.6 << 0.1;
        QTest::addRow("V=0.02 eta=1.1 vc=0.05") << 0.02 << 1.1 << 0.05;
        QTest::addRow("V=0.2 eta=0.2 vc=0.2") << 0.2 << 0.2 << 0.2;
    }
    void eq5SteadySliding() {
        QFETCH(double, V);
        QFETCH(double, eta);
        QFETCH(double, vc);
        RateStateParams p;
        p.eta_s_per_m = eta;
        p.vc_mps = vc;
        p.epsT_N_per_m = 1e6;
        const RateStateLaw law{p};
        const double tN = 6.2;
        const double dt = 0.1 * p.Dc_m / std::abs(V);
        ReturnMapResult last;
        const LawState s = slideAt(law, tN, LawState{}, V, dt, 3000, &last);
        const double expected = eq5Ratio(p, V);
        QVERIFY(!last.stuck);
        QVERIFY(last.converged);
        QVERIFY2(relDiff(std::abs(s.force_N) / tN, expected) < 1e-6,
                 qPrintable(QString("|F|/tN = %1, Eq. 5 gives %2").arg(std::abs(s.force_N) / tN, 0, 'g', 15).arg(expected, 0, 'g', 15)));
        QVERIFY(s.force_N * V > 0.0);  // friction on the slider acts along the relative velocity
        QVERIFY(relDiff(s.alpha, -std::abs(V) / vc) < 1e-6);
        QVERIFY(relDiff(last.slipIncrement_m / dt, std::abs(V)) < 1e-6);
        // The law's own closed forms agree with the independent one.
        QVERIFY(relDiff(law.steadyStateRatio(V), expected) < 1e-12);
        QVERIFY(relDiff(law.steadyStateAlpha(V), -std::abs(V) / vc) < 1e-12);
        QVERIFY(relDiff(steadyStateRatio(FrictionLaw{law}, V), expected) < 1e-12);
        // Eq. 2's rate form (used by the TR-BDF2 step): α̇ = 0 at the steady state, and the
        // backward-Euler α update of a small step has α̇ as its slope.
        QVERIFY(std::abs(law.alphaRate(law.steadyStateAlpha(V), std::abs(V))) < 1e-9 * std::abs(V) / p.Dc_m);
        const double a0 = -0.3, rate = 0.02, h = 1e-10;
        const double beAlpha = (a0 - rate * rate * h / (p.Dc_m * vc)) / (1.0 + rate * h / p.Dc_m);  // rate_state.cpp
        QVERIFY(relDiff((beAlpha - a0) / h, law.alphaRate(a0, rate)) < 1e-5);  // O(λ̇h/D_c) = 1e-7
        QVERIFY(relDiff(law.alphaRate(a0, rate), -rate / p.Dc_m * (a0 + rate / vc)) < 1e-14);
        QCOMPARE(law.alphaRate(a0, 0.0), 0.0);
    }

    // The same through the prescribed-slip set-up (simulatePrescribed from a velocity history).
    void eq5ThroughPrescribedSetup() {
        const RateStateParams p;
        const FrictionLaw law = RateStateLaw{p};
        const double tN = 6.2, V = 0.03;
        const double dt = 0.1 * p.Dc_m / V;
        std::vector<double> t, v;
        for (int i = 0; i <= 3000; ++i) { t.push_back(i * dt); v.push_back(V); }
        const RunResult r = simulatePrescribed(law, tN, SlipHistory::fromVelocity(t, v), 1);
        QVERIFY2(r.ok(), r.message.c_str());
        QCOMPARE(r.samples.size(), t.size());
        QVERIFY(relDiff(r.samples.back().ratio, eq5Ratio(p, V)) < 1e-6);
        QVERIFY(relDiff(r.samples.back().slipRate_mps, V) < 1e-6);
    }

    // Coulomb: steady sliding at μ whatever the speed (rate independent).
    void eq5Coulomb() {
        const CoulombLaw law{CoulombParams{}};
        const double tN = 6.2;
        for (double V : {1e-4, 0.1, -0.5}) {
            LawState s;
            // 100 steps of 1e-6 m slip: the elastic trial exceeds μ t_N = 1.55 N after 2 steps.
            for (int i = 0; i < 100; ++i) s = law.returnMap(s, std::copysign(1e-6, V), 1e-6 / std::abs(V), tN).state;
            QCOMPARE(s.force_N, std::copysign(0.25 * tN, V));
            QCOMPARE(law.steadyStateRatio(V), 0.25);
        }
    }

    // Eq. 6: a velocity jump V1 → V2 changes |F|/t_N by η (V2 − V1) instantly, with α unchanged.
    // "Instantly" means after the force relaxation time τ = η t_N / ε_T but before α moves over
    // the slip distance D_c. With ε_T = 1e10 N/m ("large"), τ = 0.37 ns; we look after 40 steps
    // of 0.1 ns (BE residual of the jump (1+dt/τ)^-40 ≈ 7e-5). The slip in that time is
    // ≤ 0.1 m/s · 4e-9 s = 4e-10 m = 2e-5 D_c, so α moves ≤ 2e-5 of the way to its new steady
    // value −C2 V2 (Eq. 2 with α ≈ −C2 V1), and K1 by ≤ C1·2e-5·C2|ΔV| ≈ 1e-4 of ηΔV.
    // So 1e-3 relative holds for a correct law and fails for a missing or wrong η term or a
    // state that jumps with V.
    void eq6VelocityJump_data() {
        QTest::addColumn<double>("V1");
        QTest::addColumn<double>("V2");
        QTest::addRow("0.01->0.02") << 0.01 << 0.02;
        QTest::addRow("0.05->0.01") << 0.05 << 0.01;
        QTest::addRow("0.001->0.1") << 0.001 << 0.1;
        QTest::addRow("0.2->0.05") << 0.2 << 0.05;
    }
    void eq6VelocityJump() {
        QFETCH(double, V1);
        QFETCH(double, V2);
        RateStateParams p;
        p.epsT_N_per_m = 1e10;
        const RateStateLaw law{p};
        const double tN = 6.2;
        // Steady state at V1 (Δλ = D_c/10 per step, as in eq5).
        const LawState s1 = slideAt(law, tN, LawState{}, V1, 0.1 * p.Dc_m / V1, 3000);
        QVERIFY(relDiff(s1.force_N / tN, eq5Ratio(p, V1)) < 1e-6);
        const LawState s2 = slideAt(law, tN, s1, V2, 1e-10, 40);
        const double jump = (s2.force_N - s1.force_N) / tN;
        const double expected = p.eta_s_per_m * (V2 - V1);
        QVERIFY2(std::abs(jump - expected) < 1e-3 * std::abs(expected),
                 qPrintable(QString("jump %1, eta dV = %2").arg(jump, 0, 'g', 10).arg(expected, 0, 'g', 10)));
        // "α unchanged": it has moved less than 1e-3 of the way to its new steady value −C2 V2
        // (the bound above gives ≤ 2e-5 of the way).
        const double alphaMove = std::abs(law.steadyStateAlpha(V2) - s1.alpha);
        QVERIFY2(std::abs(s2.alpha - s1.alpha) < 1e-3 * alphaMove,
                 qPrintable(QString("alpha %1 -> %2 (steady %3)").arg(s1.alpha).arg(s2.alpha).arg(law.steadyStateAlpha(V2))));
        // And long after the jump the law settles on the new Eq. 5 branch.
        const LawState s3 = slideAt(law, tN, s2, V2, 0.1 * p.Dc_m / V2, 3000);
        QVERIFY(relDiff(s3.force_N / tN, eq5Ratio(p, V2)) < 1e-6);
    }

    // Consistent tangent: the returned dF_{n+1}/dΔg equals a central finite difference of
    // F_{n+1}(Δg). Step h = 1e-4 of the trial's distance to the slip surface (in slip units),
    // so both FD points stay on the same side of the stick/slip kink. FD truncation is
    // O(h² F''') and the local solve is exact to ~1e-13 (a+t_N), i.e. ≤ 1e-12 N / h; we allow
    // 1e-6 relative to ε_T plus 1e-5 relative to the tangent itself. A tangent that ignored
    // the state (dα/dΔλ) or the viscous term would be off by far more than that.
    void consistentTangent_data() {
        QTest::addColumn<bool>("coulomb");
        QTest::addColumn<double>("epsT");
        QTest::addColumn<double>("eta");
        QTest::addColumn<double>("dt");
        QTest::addColumn<double>("F0");
        QTest::addColumn<double>("alpha0");
        QTest::addColumn<double>("phiTarget");  // Φ_trial / t_N we aim at (negative: stick)
        for (bool coulomb : {false, true})
            for (double epsT : {1e4, 1e6, 1e8})
                for (double dt : {1e-6, 1e-4})
                    for (double phi : {-0.1, 0.02, 0.5})
                        for (double alpha : {0.0, -0.3}) {
                            if (coulomb && alpha != 0.0) continue;
                            QTest::addRow("%s eps=%g dt=%g phi=%g alpha=%g", coulomb ? "coulomb" : "rate-state", epsT,
                                          dt, phi, alpha)
                                << coulomb << epsT << 0.6 << dt << 0.3 << alpha << phi;
                            if (!coulomb)
                                QTest::addRow("rate-state eta=5 F0<0 eps=%g dt=%g phi=%g alpha=%g", epsT, dt, phi, alpha)
                                    << false << epsT << 5.0 << dt << -1.0 << alpha << phi;
                        }
    }
    void consistentTangent() {
        QFETCH(bool, coulomb);
        QFETCH(double, epsT);
        QFETCH(double, eta);
        QFETCH(double, dt);
        QFETCH(double, F0);
        QFETCH(double, alpha0);
        QFETCH(double, phiTarget);
        const double tN = 6.2;
        RateStateParams rp;
        rp.epsT_N_per_m = epsT;
        rp.eta_s_per_m = eta;
        CoulombParams cp;
        cp.epsT_N_per_m = epsT;
        const FrictionLaw law = coulomb ? FrictionLaw{CoulombLaw{cp}} : FrictionLaw{RateStateLaw{rp}};
        const LawState s0{F0, alpha0, {}};
        // Slip strength at the current state, t_N (μ + K1(α_n)).
        const double strength = coulomb ? cp.mu * tN : tN * (rp.mu + RateStateLaw{rp}.K1(alpha0));
        // Choose Δg so that |F_trial| = strength + phiTarget·t_N in the direction of F0.
        const double dir = F0 >= 0 ? 1.0 : -1.0;
        const double dg = (dir * (strength + phiTarget * tN) - F0) / epsT;
        const ReturnMapResult r = returnMap(law, s0, dg, dt, tN);
        QVERIFY(r.converged);
        QCOMPARE(r.stuck, phiTarget < 0);
        const double h = 1e-4 * std::abs(phiTarget) * tN / epsT;
        const double Fp = returnMap(law, s0, dg + h, dt, tN).state.force_N;
        const double Fm = returnMap(law, s0, dg - h, dt, tN).state.force_N;
        const double fd = (Fp - Fm) / (2 * h);
        const double tol = 1e-6 * epsT + 1e-5 * std::abs(fd);
        QVERIFY2(std::abs(r.tangent_N_per_m - fd) <= tol,
                 qPrintable(QString("tangent %1, central FD %2").arg(r.tangent_N_per_m, 0, 'g', 12).arg(fd, 0, 'g', 12)));
        if (phiTarget < 0) QCOMPARE(r.tangent_N_per_m, epsT);  // stick: pure elastic predictor
        // In slip the tangent is softer than ε_T and never negative for these (rate-strengthening
        // over one step) states.
        if (phiTarget > 0) QVERIFY(r.tangent_N_per_m < epsT && r.tangent_N_per_m >= 0.0);
    }

    // Robustness: the local solve converges over ε_T 1e3…1e9 N/m and η 1e-3…10 s/m, a grid of
    // Δg (±, 1e-10…1e-3 m), Δt (1e-7…1e-3 s) and start states. At convergence the discrete
    // flow rule Φ_{n+1} = η t_N Δλ/Δt holds (Eq. 3, backward Euler). Two scales for its residual:
    //  - relative to |F_trial| + t_N, the scale the solve starts from: the solver stops at
    //    |R| ≤ 1e-13 (|F_tr| + t_N), and F_{n+1} = s(|F_tr| − ε Δλ) cancels digits when
    //    |F_tr| ≫ F (up to 1e6 N here), so round-off is ~1e-16 |F_tr|. We allow 1e-9.
    //  - relative to |F_{n+1}| + t_N, the force the simulation goes on with: it should be
    //    accurate to 1e-6 of itself (far below the 1e-3 target of the scheme); the worst case
    //    is a 1e6 N trial returned to 0.6 N, where the 1e-13 |F_tr| stopping residual is 1e-8.
    void convergesOverRange() {
        const double tN = 6.2;
        long cases = 0, slipCases = 0;
        int maxIts = 0;
        double worstTrial = 0, worstForce = 0;
        QString worstWhere;
        for (double epsT = 1e3; epsT <= 1.001e9; epsT *= 10)
            for (double eta : {1e-3, 1e-2, 0.1, 1.0, 10.0})
                for (double dt : {1e-7, 1e-5, 1e-3})
                    for (double dg : {1e-10, -1e-8, 1e-6, -1e-5, 1e-4, 1e-3})
                        for (double alpha0 : {0.0, -2.0, 0.3})
                            for (double F0 : {0.0, 1.5, -1.0}) {
                                RateStateParams p;
                                p.epsT_N_per_m = epsT;
                                p.eta_s_per_m = eta;
                                const RateStateLaw law{p};
                                const LawState s0{F0, alpha0, {}};
                                const ReturnMapResult r = law.returnMap(s0, dg, dt, tN);
                                ++cases;
                                const QString where = QString("epsT=%1 eta=%2 dt=%3 dg=%4 alpha=%5 F0=%6")
                                                          .arg(epsT).arg(eta).arg(dt).arg(dg).arg(alpha0).arg(F0);
                                QVERIFY2(r.converged, qPrintable(where));
                                QVERIFY2(std::isfinite(r.state.force_N) && std::isfinite(r.state.alpha) &&
                                             std::isfinite(r.slipIncrement_m) && std::isfinite(r.tangent_N_per_m),
                                         qPrintable(where));
                                QVERIFY2(r.slipIncrement_m >= 0.0, qPrintable(where));
                                const double trial = F0 + epsT * dg;
                                if (r.stuck) {
                                    QVERIFY2(law.slipFunction(r.state, tN) <= 1e-12 * (std::abs(trial) + tN), qPrintable(where));
                                    QCOMPARE(r.state.force_N, trial);
                                    QCOMPARE(r.state.alpha, alpha0);
                                    continue;
                                }
                                ++slipCases;
                                maxIts = std::max(maxIts, r.iterations);
                                const double phi = law.slipFunction(r.state, tN);
                                const double flow = eta * tN * r.slipIncrement_m / dt;
                                const double eTrial = std::abs(phi - flow) / (std::abs(trial) + tN);
                                const double eForce = std::abs(phi - flow) / (std::abs(r.state.force_N) + tN);
                                QVERIFY2(eTrial <= 1e-9,
                                         qPrintable(where + QString(": Phi=%1, eta tN dl/dt=%2").arg(phi).arg(flow)));
                                if (eForce > worstForce) {
                                    worstForce = eForce;
                                    worstWhere = where + QString(": Phi=%1, eta tN dl/dt=%2").arg(phi, 0, 'g', 10).arg(flow, 0, 'g', 10);
                                }
                                worstTrial = std::max(worstTrial, eTrial);
                                // Radial return: the force keeps the trial's sign and does not grow.
                                QVERIFY2(r.state.force_N * trial >= 0.0 && std::abs(r.state.force_N) <= std::abs(trial),
                                         qPrintable(where));
                                // Slip never exceeds the trial's elastic over-stretch.
                                QVERIFY2(r.slipIncrement_m * epsT <= std::abs(trial) * (1 + 1e-12), qPrintable(where));
                            }
        qInfo("return map: %ld cases, %ld slipping, at most %d local iterations", cases, slipCases, maxIts);
        qInfo("flow-rule residual: worst %.3g of |F_trial|+tN, worst %.3g of |F|+tN (%s)", worstTrial, worstForce,
              qPrintable(worstWhere));
        QVERIFY(slipCases > cases / 4);  // the grid really exercises the slip branch
        QVERIFY2(worstForce <= 1e-6, qPrintable(worstWhere));
    }

    // The return map from a given trial force with a softer return stiffness k_r (the contact
    // in series with a structure of stiffness K: k_r = ε_T K/(K + ε_T), used by the condensed
    // Newmark step). With k_r = ε_T it is returnMap itself. Otherwise, in slip:
    //   F_{n+1} = s (|F_tr| − k_r Δλ),  α_{n+1} = (α_n − C2 Δλ²/(D_c Δt))/(1 + Δλ/D_c)  (Eq. 2, BE),
    //   Φ(F_{n+1}, α_{n+1}) = η t_N Δλ/Δt (Eq. 3, BE); Coulomb: |F| = μ t_N, Δλ = (|F_tr| − μ t_N)/k_r;
    // and tangent_N_per_m = ε_T dF/dF_tr (central FD with a 1e-4 relative step; same tolerance
    // reasoning as consistentTangent).
    void returnMapFromTrialInSeries() {
        const double tN = 6.2, eps = 1e6, dt = 1e-5;
        RateStateParams rp;
        rp.epsT_N_per_m = eps;
        CoulombParams cp;
        cp.epsT_N_per_m = eps;
        const RateStateLaw rs{rp};
        const CoulombLaw cl{cp};
        for (double K : {1e3, 1e5, 1e7, 1e12})
            for (double Ftr : {1.0, 1.7, -2.5, 8.0})
                for (double alpha0 : {0.0, -0.2}) {
                    const double kr = eps * K / (K + eps);
                    const LawState s0{0.4, alpha0, {}};
                    const QString where = QString("K=%1 Ftr=%2 alpha=%3").arg(K).arg(Ftr).arg(alpha0);
                    // k_r = ε_T: the plain return map.
                    const ReturnMapResult plain = rs.returnMap(s0, (Ftr - s0.force_N) / eps, dt, tN);
                    const ReturnMapResult same = rs.returnMapFromTrial(s0, Ftr, eps, dt, tN);
                    QVERIFY2(std::abs(plain.state.force_N - same.state.force_N) <= 1e-12 * (std::abs(Ftr) + tN), qPrintable(where));
                    // Rate-state in series.
                    const ReturnMapResult r = rs.returnMapFromTrial(s0, Ftr, kr, dt, tN);
                    QVERIFY2(r.converged, qPrintable(where));
                    const double sg = Ftr >= 0 ? 1.0 : -1.0;
                    if (rs.slipFunction({Ftr, alpha0, {}}, tN) <= 0) {
                        QVERIFY2(r.stuck && r.state.force_N == Ftr && r.slipIncrement_m == 0, qPrintable(where));
                    } else {
                        QVERIFY2(!r.stuck, qPrintable(where));
                        const double dl = r.slipIncrement_m;
                        QVERIFY2(std::abs(r.state.force_N - sg * (std::abs(Ftr) - kr * dl)) <= 1e-12 * (std::abs(Ftr) + tN),
                                 qPrintable(where));
                        const double alphaBE = (alpha0 - rp.C2() * dl * dl / (rp.Dc_m * dt)) / (1 + dl / rp.Dc_m);
                        QVERIFY2(std::abs(r.state.alpha - alphaBE) <= 1e-12 * (1 + std::abs(alphaBE)), qPrintable(where));
                        QVERIFY2(std::abs(rs.slipFunction(r.state, tN) - rp.eta_s_per_m * tN * dl / dt) <= 1e-9 * (std::abs(Ftr) + tN),
                                 qPrintable(where));
                        const double h = 1e-4 * rs.slipFunction({Ftr, alpha0, {}}, tN);
                        const double fd = (rs.returnMapFromTrial(s0, Ftr + sg * h, kr, dt, tN).state.force_N -
                                           rs.returnMapFromTrial(s0, Ftr - sg * h, kr, dt, tN).state.force_N) / (2 * sg * h);
                        QVERIFY2(std::abs(r.tangent_N_per_m - eps * fd) <= 1e-6 * eps + 1e-5 * eps * std::abs(fd),
                                 qPrintable(where + QString(": tangent %1, eps dF/dFtr %2").arg(r.tangent_N_per_m).arg(eps * fd)));
                    }
                    // Coulomb in series.
                    const ReturnMapResult c = cl.returnMapFromTrial(s0, Ftr, kr, dt, tN);
                    const double muTN = cp.mu * tN;
                    if (std::abs(Ftr) <= muTN) {
                        QVERIFY2(c.stuck && c.state.force_N == Ftr, qPrintable(where));
                        QCOMPARE(cl.slipFunction(c.state, tN), std::abs(Ftr) - muTN);
                    } else {
                        QVERIFY2(!c.stuck && c.state.force_N == sg * muTN, qPrintable(where));
                        QVERIFY2(std::abs(c.slipIncrement_m - (std::abs(Ftr) - muTN) / kr) <= 1e-12 * std::abs(Ftr) / kr, qPrintable(where));
                        QCOMPARE(cl.slipFunction(c.state, tN), 0.0);
                    }
                }
    }

    // A full dynamics run at the corners of that range completes with status Ok and finite samples.
    void dynamicsAtExtremes_data() {
        QTest::addColumn<double>("epsT");
        QTest::addColumn<double>("eta");
        for (double e : {1e3, 1e9})
            for (double n : {1e-3, 10.0}) QTest::addRow("epsT=%g eta=%g", e, n) << e << n;
    }
    void dynamicsAtExtremes() {
        QFETCH(double, epsT);
        QFETCH(double, eta);
        SimParams p = fig20Params();
        p.lawParams<RateStateParams>().epsT_N_per_m = epsT;
        p.lawParams<RateStateParams>().eta_s_per_m = eta;
        p.cycles = 2;
        const RunResult r = simulateDynamics(p);
        QVERIFY2(r.ok(), r.message.c_str());
        QVERIFY(allFinite(r.samples));
        QCOMPARE(r.samples.size(), size_t(2 * 100 + 1));
    }
};

QTEST_GUILESS_MAIN(TstReturnMap)
#include "tst_return_map.moc"
