// The paper's recipes on runs of this project's own prescribed-slip simulation, where the
// answer is known from the law: the pull peak is μ (+ at most η·v), the impulse gives η.
#include <QtTest>

#include <cmath>

#include "core/friction/friction_law.hpp"
#include "core/identify/recipes.hpp"
#include "core/integrate/prescribed.hpp"

using namespace stickslip;
using namespace stickslip::identify;

class TstRecipes : public QObject {
    Q_OBJECT
private slots:
    // Fig. 14a–b: stage pulled at constant velocity from rest.
    void pullPeakGivesMu() {
        RateStateParams p;
        p.mu = 0.3; p.C1 = 0.3; p.eta_s_per_m = 0.05; p.Dc_m = 20e-6; p.vc_mps = 0.1; p.epsT_N_per_m = 1e6;
        const double tN = 6.2, v0 = 0.01;
        std::vector<double> t, V;
        for (int i = 0; i <= 20000; ++i) { t.push_back(i * 1e-5); V.push_back(v0); }
        const SlipHistory h = SlipHistory::fromVelocity(t, V);
        const RunResult r = simulatePrescribed(FrictionLaw{RateStateLaw{p}}, tN, h, 2);
        QVERIFY(r.ok());
        std::vector<double> F, Vs;
        for (const Sample& s : r.samples) { F.push_back(s.force_N); Vs.push_back(s.relVel_mps); }
        const PullEstimate e = muFromPull(Vs, F, tN);
        QVERIFY2(e.ok, e.message.c_str());
        QVERIFY(e.mu >= p.mu - 1e-6);
        QVERIFY2(e.mu <= p.mu + p.eta_s_per_m * v0 + 1e-6, qPrintable(QString::number(e.mu)));
        // The plateau is the steady sliding ratio of Eq. 5, below the peak (velocity weakening).
        const RateStateLaw law{p};
        QVERIFY(std::abs(e.kineticRatio - law.steadyStateRatio(v0)) < 1e-3);
        QVERIFY(e.kineticRatio < e.mu);
        QVERIFY(std::abs(e.pullVelocity_mps - v0) < 1e-9);
    }

    // Eq. 7: a velocity jump at fixed state gives Δ(F/t_N) = η Δv.
    void impulseGivesEta() {
        RateStateParams p;
        p.mu = 0.25; p.C1 = 0.25; p.eta_s_per_m = 0.6; p.Dc_m = 20e-6; p.vc_mps = 0.1; p.epsT_N_per_m = 1e8;
        const double tN = 6.2, v1 = 0.05, v2 = 0.15, dt = 1e-7;
        std::vector<double> t, V;
        for (int i = 0; i <= 22000; ++i) { t.push_back(i * dt); V.push_back(i <= 20000 ? v1 : v2); }
        const RunResult r = simulatePrescribed(FrictionLaw{RateStateLaw{p}}, tN, SlipHistory::fromVelocity(t, V), 1);
        QVERIFY(r.ok());
        std::vector<double> F;
        for (const Sample& s : r.samples) F.push_back(s.force_N);
        const ImpulseEstimate e = etaFromImpulse(V, F, tN, 1, 5);
        QVERIFY2(e.ok, e.message.c_str());
        QCOMPARE(e.index, size_t(20000));
        QVERIFY(std::abs(e.dv_mps - (v2 - v1)) < 1e-12);
        QVERIFY2(std::abs(e.eta_s_per_m - p.eta_s_per_m) < 0.02 * p.eta_s_per_m, qPrintable(QString::number(e.eta_s_per_m)));
    }

    void degenerateInputsAreReported() {
        const std::vector<double> zero(10, 0.0), f(10, 1.0);
        QVERIFY(!muFromPull(zero, f, 1.0).ok);
        QVERIFY(!muFromPull(f, f, 0.0).ok);
        const ImpulseEstimate e = etaFromImpulse(zero, f, 1.0);
        QVERIFY(!e.ok);
        QVERIFY(!e.message.empty());
    }
};

QTEST_GUILESS_MAIN(TstRecipes)
#include "tst_recipes.moc"
