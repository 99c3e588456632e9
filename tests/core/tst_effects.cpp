// The missing-effect catalogue and the extended model: each effect does what its file says.
#include <QtTest/QtTest>

#include <cmath>
#include <random>

#include "core/friction/rate_state.hpp"
#include "core/identify/effects/registry.hpp"
#include "core/identify/extended_model.hpp"
#include "core/integrate/dynamics.hpp"

using namespace stickslip;
using namespace stickslip::identify;

namespace {

// Constant-velocity slide: g = v t over `seconds`, sampled at 1/dt.
void ramp(double v, double seconds, double dt, std::vector<double>& t, std::vector<double>& g) {
    t.clear(); g.clear();
    for (double tt = 0; tt <= seconds + 1e-12; tt += dt) { t.push_back(tt); g.push_back(v * tt); }
}

ExtendedModel baseModel() {
    ExtendedModel m;
    m.law.mu = 0.25; m.law.C1 = 0.25; m.law.eta_s_per_m = 0.6; m.law.Dc_m = 20e-6; m.law.vc_mps = 0.1;
    m.law.epsT_N_per_m = 1e6;
    m.tNref_N = 6.2;
    return m;
}

}  // namespace

class TestEffects : public QObject {
    Q_OBJECT
private slots:
    void catalogueHasTheNamesTheReportUses() {
        const std::vector<std::string> want = {"frictional_lag", "normal_load_mu", "direction_asymmetry", "wear_drift", "stick_healing",
                                               "backlash", "presliding_compliance", "viscous_damping", "sensor_inertia"};
        const auto cat = effectCatalogue();
        QCOMPARE(cat.size(), want.size());
        for (size_t i = 0; i < want.size(); ++i) {
            QCOMPARE(cat[i].name, want[i]);
            QVERIFY(cat[i].description.size() > 100);
            QVERIFY(!cat[i].signature.empty());
            QVERIFY(!cat[i].params.empty());
            QVERIFY(!cat[i].pointers.empty());
            for (const auto& p : cat[i].params) {
                QVERIFY(p.lower < p.upper);
                QVERIFY(p.initial >= p.lower && p.initial <= p.upper);
                if (p.logScale) QVERIFY(p.lower > 0);
            }
        }
    }
    void setGetClearRoundTrip() {
        EffectSet s;
        QVERIFY(s.names().empty());
        QVERIFY(setEffect(s, "stick_healing", {0.1, 0.2, 1e-4}));
        QVERIFY(setEffect(s, "backlash", {1e-4}));
        std::vector<double> v;
        QVERIFY(getEffect(s, "stick_healing", v));
        QCOMPARE(v.size(), size_t(3));
        QCOMPARE(v[1], 0.2);
        QCOMPARE(s.names(), (std::vector<std::string>{"stick_healing", "backlash"}));
        std::string err;
        QVERIFY(!setEffect(s, "stick_healing", {0.1}, &err));
        QVERIFY(err.find("3 parameter") != std::string::npos);
        QVERIFY(!setEffect(s, "teleportation", {1.0}, &err));
        QVERIFY(err.find("unknown effect") != std::string::npos);
        clearEffect(s, "backlash");
        QVERIFY(!getEffect(s, "backlash", v));
        EffectInfo info;
        QVERIFY(findEffect("wear_drift", info));
        QVERIFY(!findEffect("nope", info));
    }
    void noEffectsEqualsTheBaseLaw() {
        const ExtendedModel m = baseModel();
        const ExtendedLaw ext = ExtendedLaw::make(m);
        const RateStateLaw base{m.law};
        LawState a = ext.initialState({6.2, 0}), b;
        for (int i = 0; i < 20000; ++i) {
            const double t = i * 1e-4;
            const double dg = 2e-3 * 2 * M_PI * 3 * std::cos(2 * M_PI * 3 * t) * 1e-4;
            const auto ra = ext.returnMap(a, dg, 1e-4, 6.2);
            const auto rb = base.returnMap(b, dg, 1e-4, 6.2);
            QVERIFY(std::abs(ra.state.force_N - rb.state.force_N) < 1e-8);
            QVERIFY(std::abs(ra.state.alpha - rb.state.alpha) < 1e-8);
            a = ra.state; b = rb.state;
        }
    }
    // The per-loop scratch (step constants, exp(α/r) of a stuck state, the skipped zero-force
    // check) is an optimisation only: with and without it every state is bit for bit the same,
    // with each effect that changes the return map and with all of them, through stick and slip.
    void cachedReturnMapIsBitIdentical() {
        for (const StateStep step : {StateStep::BackwardEuler, StateStep::ConstantRate})
        for (const char* name : {"", "normal_load_mu", "direction_asymmetry", "wear_drift", "stick_healing", "backlash",
                                 "presliding_compliance", "frictional_lag", "all"}) {
            ExtendedModel m = baseModel();
            m.stateStep = step;
            for (const EffectInfo& e : effectCatalogue()) {
                if (std::string(name) != "all" && e.name != name) continue;
                std::vector<double> v;
                for (const auto& p : e.params) v.push_back(p.initial);
                QVERIFY(setEffect(m.effects, e.name, v));
            }
            const ExtendedLaw law = ExtendedLaw::make(m);
            ExtendedLaw::ExpCache cache;
            LawState a = law.initialState({6.2, 0}), b = a;
            long stuck = 0, slid = 0;
            for (int i = 0; i < 20000; ++i) {
                const double t = i * 1e-4, w = 2 * M_PI * 3;
                // Stage-like slip with a slow modulation, so that the contact sticks and slides.
                const double dg = 1.5e-3 * w * std::cos(w * t) * (1.0 + 0.3 * std::sin(0.7 * w * t)) * 1e-4;
                const double dt = i % 7 == 0 ? 0.5e-4 : 1e-4;  // the step constants change too
                const auto ra = law.returnMap(a, dg, dt, 6.2, &cache);
                const auto rb = law.returnMap(b, dg, dt, 6.2);
                QCOMPARE(ra.state.force_N, rb.state.force_N);
                QCOMPARE(ra.state.alpha, rb.state.alpha);
                for (size_t k = 0; k < a.aux.size(); ++k) QCOMPARE(ra.state.aux[k], rb.state.aux[k]);
                QCOMPARE(ra.tangent_N_per_m, rb.tangent_N_per_m);
                QCOMPARE(ra.slipIncrement_m, rb.slipIncrement_m);
                (ra.slipIncrement_m > 0 ? slid : stuck) += 1;
                a = ra.state;
                b = rb.state;
            }
            QVERIFY2(stuck > 200 && slid > 1000, qPrintable(QString("%1: %2 stuck, %3 slid").arg(name).arg(stuck).arg(slid)));
        }
    }
    // StateStep::ConstantRate advances α exactly for a slip rate constant over the step. Along a
    // slip history made of constant-rate pieces (0.02 → 0.08 → 0.03 m/s, the steps 2 ms, so
    // Δλ/D_c reaches 8) its α at every step end equals the closed form of Eq. 2 for that piece to
    // round-off, while backward Euler's relaxation factor 1/(1 + Δλ/D_c) leaves an error of
    // order one; both reach the steady state α = −C2 V (Eq. 5).
    void constantRateStateStepIsExactPerPiece() {
        ExtendedModel m = baseModel();
        m.law.eta_s_per_m = 0.0;  // the rate of slip then equals the prescribed one once sliding
        const double dt = 2e-3, Dc = m.law.Dc_m, C2 = m.law.C2();
        std::vector<double> t = {0.0}, g = {0.0}, V;
        for (double v : {0.02, 0.08, 0.03})
            for (int i = 0; i < 40; ++i) { t.push_back(t.back() + dt); g.push_back(g.back() + v * dt); V.push_back(v); }
        double worstExact = 0, worstBe = 0;
        for (const StateStep step : {StateStep::ConstantRate, StateStep::BackwardEuler}) {
            m.stateStep = step;
            const ExtendedLaw law = ExtendedLaw::make(m);
            LawState s = law.initialState({6.2, 0});
            double& worst = step == StateStep::ConstantRate ? worstExact : worstBe;
            long compared = 0;
            for (size_t i = 1; i < t.size(); ++i) {
                const double a0 = s.alpha;
                const ReturnMapResult r = law.returnMap(s, g[i] - g[i - 1], dt, 6.2);
                QVERIFY(r.converged);
                s = r.state;
                if (r.stuck || r.slipIncrement_m <= 0.0) continue;
                // Eq. 2 at the step's own slip rate Δλ/Δt, from α₀, over Δλ.
                const double rate = r.slipIncrement_m / dt, x = r.slipIncrement_m / Dc;
                const double exact = -C2 * rate + (a0 + C2 * rate) * std::exp(-x);
                const double err = std::abs(s.alpha - exact) / (C2 * rate);
                worst = std::max(worst, err);
                ++compared;
            }
            QVERIFY(compared > 100);
            QVERIFY2(std::abs(s.alpha + C2 * V.back()) < 1e-6 * C2 * V.back(), qPrintable(QString::number(s.alpha)));
        }
        qInfo("alpha error / C2 V: constant rate %.2e, backward Euler %.2e", worstExact, worstBe);
        QVERIFY(worstExact < 1e-10);
        QVERIFY(worstBe > 0.1);
    }
    // stateLowerBound (the return map's zero-force certificate) is below the state either step
    // reaches, over random states, slips and rates, within 1 % of |α_n| + C2 Δλ/Δt of it for slips under
    // D_c/10 (so that it certifies), and equal to backward Euler's value; and with it a step
    // of the extended law that slides to zero force (C1 > μ, fast, little viscosity) still does.
    void stateLowerBoundIsBelowTheStep() {
        std::mt19937_64 rng(11);
        std::uniform_real_distribution<double> U(0.0, 1.0);
        double worstClose = 0;
        for (int i = 0; i < 100000; ++i) {
            const double a0 = -60.0 + 65.0 * U(rng), Dc = std::pow(10.0, -7.0 + 4.0 * U(rng));
            const double x = Dc * std::pow(10.0, -4.0 + 7.0 * U(rng)), c = std::pow(10.0, -2.0 + 8.0 * U(rng));
            const double exact = (a0 + c * x) * std::exp(-x / Dc) - c * x;
            const double lb = stateLowerBound(StateStep::ConstantRate, a0, x, c, 1.0 / Dc);
            QVERIFY2(lb <= exact + 1e-12 * (std::abs(exact) + std::abs(a0) + c * x),
                     qPrintable(QString("a0=%1 x=%2 Dc=%3 c=%4: %5 > %6").arg(a0).arg(x).arg(Dc).arg(c).arg(lb).arg(exact)));
            if (x < 0.1 * Dc) worstClose = std::max(worstClose, (exact - lb) / (std::abs(a0) + c * x));
            const double be = (a0 - c * x * x / Dc) / (1.0 + x / Dc);
            QVERIFY(std::abs(stateLowerBound(StateStep::BackwardEuler, a0, x, c, 1.0 / Dc) - be) <= 1e-12 * (std::abs(be) + 1.0));
        }
        qInfo("constant rate: bound within %.3g of |alpha_n| + C2 x/dt for slips below Dc/10", worstClose);
        QVERIFY(worstClose < 0.01);
        for (const StateStep step : {StateStep::ConstantRate, StateStep::BackwardEuler}) {
            ExtendedModel m = baseModel();
            m.law.mu = 0.05; m.law.C1 = 0.5; m.law.eta_s_per_m = 1e-6;
            m.stateStep = step;
            const ExtendedLaw law = ExtendedLaw::make(m);
            const ReturnMapResult r = law.returnMap(law.initialState({6.2, 0}), 1e-3, 1e-5, 6.2);
            QCOMPARE(r.state.force_N, 0.0);
            QCOMPARE(r.slipIncrement_m, 1e-3);
        }
    }
    // The slip solve returns the first root of R (slip_first_root.hpp). The case is one of D13's
    // baseline scan points (ε_T = 1000 N/m, D_c = 0.32 µm, 1 ms step) where the solve from the
    // elastic–viscous predictor slipped 1.9e-4 m, while R, evaluated here from Eq. 2's
    // constant-rate step and the flow rule independently of the law's code, changes sign first
    // near 8e-7 m (docs/identify-results.md, sessions 53 and 54).
    void slipSolveReturnsTheSmallestRoot() {
        ExtendedModel m;
        m.law.mu = 0.12330588528550623; m.law.C1 = 0.12330588528550623; m.law.eta_s_per_m = 0.29593412468521496;
        m.law.Dc_m = 3.1622776601683792e-07; m.law.r = 1.0; m.law.vc_mps = 0.1; m.law.epsT_N_per_m = 1000.0;
        m.stateStep = StateStep::ConstantRate;
        const ExtendedLaw law = ExtendedLaw::make(m);
        LawState s;
        s.force_N = -0.44413850167024899;
        s.alpha = -0.11198766940828765;
        const double trial = 0.49004786365705538, tN = 4.0263284300000137, dt = 1e-3, eps = 1000.0;
        const ReturnMapResult r = law.returnMap(s, (trial - s.force_N) / eps, dt, tN);
        QVERIFY(r.converged && r.slipIncrement_m > 0.0);
        const double visc = m.law.eta_s_per_m * tN / dt, c = m.law.C2() / dt;
        auto R = [&](double x) {
            const double alpha = (s.alpha + c * x) * std::exp(-x / m.law.Dc_m) - c * x;
            return trial - eps * x - tN * (m.law.mu + m.law.C1 * (std::exp(alpha / m.law.r) - 1.0)) - visc * x;
        };
        double firstNegative = -1.0;
        for (int q = 1; q < 4000 && firstNegative < 0.0; ++q)
            if (R(r.slipIncrement_m * q / 4000.0) < 0.0) firstNegative = r.slipIncrement_m * q / 4000.0;
        qInfo("return map slip %.4g m; R < 0 first at %.4g m", r.slipIncrement_m, firstNegative);
        QVERIFY(firstNegative < 0.0);  // R ≥ 0 on the grid below the slip returned: it is the first root
        QVERIFY(r.slipIncrement_m < 2e-6);
    }
    // Both steps converge to the same solution of the law as the step shrinks, and on a coarse
    // step the exact state update is the closer one (force along a sine slip, against 1 µs steps).
    void stateStepsConvergeToTheSameLaw() {
        ExtendedModel m = baseModel();
        auto force = [&](StateStep step, double dt) {
            m.stateStep = step;
            std::vector<double> t, g;
            const double w = 2 * M_PI * 3;
            for (double tt = 0; tt <= 0.5 + 1e-12; tt += dt) { t.push_back(tt); g.push_back(2e-3 * std::sin(w * tt)); }
            const auto tr = simulateExtendedPrescribed(m, {6.2, 0}, t, g, nullptr, 1);
            std::vector<double> out;  // every 10 ms
            const size_t every = static_cast<size_t>(std::lround(1e-2 / dt));
            for (size_t i = 0; i < tr.contactForce_N.size(); i += every) out.push_back(tr.contactForce_N[i]);
            return out;
        };
        const std::vector<double> ref = force(StateStep::ConstantRate, 1e-6), refBe = force(StateStep::BackwardEuler, 1e-6);
        auto dist = [](const std::vector<double>& a, const std::vector<double>& b) {
            double e = 0;
            for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) e = std::max(e, std::abs(a[i] - b[i]));
            return e;
        };
        const double limits = dist(ref, refBe);
        const double exactCoarse = dist(force(StateStep::ConstantRate, 1e-3), ref);
        const double beCoarse = dist(force(StateStep::BackwardEuler, 1e-3), ref);
        qInfo("max |F - F_ref| [N]: 1 us exact vs BE %.2e; 1 ms: exact %.3e, BE %.3e", limits, exactCoarse, beCoarse);
        QVERIFY(limits < 1e-2);
        QVERIFY(exactCoarse < beCoarse);
    }
    void steadySlidingMatchesEq5AndLoadAndDirectionShifts() {
        ExtendedModel m = baseModel();
        std::vector<double> t, g;
        ramp(0.05, 0.2, 1e-4, t, g);
        const RateStateLaw base{m.law};
        const double ss = base.steadyStateRatio(0.05);
        auto plateau = [&](const ExtendedModel& mm, double tN, double sign) {
            std::vector<double> gg = g;
            for (double& x : gg) x *= sign;
            const auto tr = simulateExtendedPrescribed(mm, {tN, 0}, t, gg, nullptr, 4);
            return tr.contactForce_N.back() / tN;
        };
        QVERIFY(std::abs(plateau(m, 6.2, 1) - ss) < 2e-3);
        m.effects.normalLoadMu = NormalLoadMu{-0.01};
        QVERIFY(std::abs(plateau(m, 10.2, 1) - (ss - 0.04)) < 2e-3);  // μ shifted by −0.01 × (10.2 − 6.2)
        m.effects.normalLoadMu.reset();
        m.effects.directionAsymmetry = DirectionAsymmetry{0.05};
        QVERIFY(std::abs(plateau(m, 6.2, 1) - ss) < 2e-3);
        QVERIFY(std::abs(plateau(m, 6.2, -1) + (ss - 0.05)) < 2e-3);
        m.effects.directionAsymmetry.reset();
        // Dieterich ageing in steady sliding: θ = D_h/V adds b ln(1 + D_h/(V t_c)).
        m.effects.stickHealing = StickHealing{0.02, 1e-3, 1e-4};
        const double heal = 0.02 * std::log1p(1e-4 / (0.05 * 1e-3));
        QVERIFY2(std::abs(plateau(m, 6.2, 1) - (ss + heal)) < 2e-3, qPrintable(QString::number(plateau(m, 6.2, 1) - ss)));
    }
    // The strength is the sum of its parts: t_N (μ + load shift + b ln(1 + θ/t_c) + C1 (e^{α/r} − 1)),
    // and a stuck returnMap step that just reaches it sits on Φ = 0.
    void lawStrengthIsTheSumOfItsParts() {
        ExtendedModel m = baseModel();
        m.effects.normalLoadMu = NormalLoadMu{-0.01};
        m.effects.stickHealing = StickHealing{0.02, 1e-3, 1e-4};
        const ExtendedLaw law = ExtendedLaw::make(m);
        LawState s;
        s.alpha = -0.3;
        s.aux[1] = 0.05;
        const double tN = 8.2;
        const double y = tN * (0.25 - 0.01 * (8.2 - 6.2) + 0.02 * std::log1p(0.05 / 1e-3) + 0.25 * std::expm1(-0.3));
        QVERIFY(std::abs(law.lawStrength(s, 1.0, tN) - y) < 1e-12 * y);
        s.force_N = y * (1 - 1e-9);
        const ReturnMapResult r = law.returnMap(s, 0.0, 1e-12, tN);
        QVERIFY(r.stuck);
        QCOMPARE(r.slipIncrement_m, 0.0);
    }
    void wearDriftGrowsWithSlipDistance() {
        ExtendedModel m = baseModel();
        m.effects.wearDrift = WearDrift{0.2};  // +0.2 per metre
        std::vector<double> t, g;
        ramp(0.05, 2.0, 1e-3, t, g);  // 0.1 m
        const auto tr = simulateExtendedPrescribed(m, {6.2, 0.5}, t, g, nullptr, 4);
        const double early = tr.contactForce_N[100] / 6.2, late = tr.contactForce_N.back() / 6.2;
        QVERIFY(std::abs((late - early) - 0.2 * (g.back() - g[100])) < 1e-3);
        QVERIFY(std::abs(tr.accumulatedSlipEnd_m - (0.5 + g.back())) < 1e-4);
    }
    void stickHealingRaisesBreakawayAfterLongStick() {
        ExtendedModel m = baseModel();
        m.effects.stickHealing = StickHealing{0.02, 0.001, 1e-4};
        // Slide, stick for T, slide again: peak ratio after the stick.
        auto peakAfterStick = [&](double T) {
            std::vector<double> t, g;
            double x = 0, tt = 0;
            const double dt = 1e-4;
            for (; tt < 0.05; tt += dt) { t.push_back(tt); g.push_back(x); x += 0.02 * dt; }
            for (double s = 0; s < T; s += dt, tt += dt) { t.push_back(tt); g.push_back(x); }
            for (double s = 0; s < 0.05; s += dt, tt += dt) { t.push_back(tt); g.push_back(x); x += 0.02 * dt; }
            const auto tr = simulateExtendedPrescribed(m, {6.2, 0}, t, g, nullptr, 2);
            double pk = 0;
            for (size_t i = t.size() - 500; i < t.size(); ++i) pk = std::max(pk, tr.contactForce_N[i] / 6.2);
            return pk;
        };
        const double shortStick = peakAfterStick(0.005), longStick = peakAfterStick(0.5);
        // The age enters the stick at its sliding value D_h/V = 5 ms, so the long stick breaks
        // away b ln((1 + 0.505/t_c)/(1 + 0.010/t_c)) = 0.02 ln(506/11) ≈ 0.077 higher.
        QVERIFY2(std::abs((longStick - shortStick) - 0.02 * std::log(506.0 / 11.0)) < 0.01,
                 qPrintable(QString::number(longStick - shortStick)));
    }
    void frictionalLagDelaysTheVelocityWeakening() {
        ExtendedModel m = baseModel();
        std::vector<double> t, g;
        const double dt = 1e-4;
        double x = 0;
        for (double tt = 0; tt < 0.3; tt += dt) {  // 0.01 m/s, then a step to 0.08 m/s
            t.push_back(tt);
            g.push_back(x);
            x += (tt < 0.15 ? 0.01 : 0.08) * dt;
        }
        const auto plain = simulateExtendedPrescribed(m, {6.2, 0}, t, g, nullptr, 2);
        m.effects.frictionalLag = FrictionalLag{0.01};
        const auto lag = simulateExtendedPrescribed(m, {6.2, 0}, t, g, nullptr, 2);
        const size_t iStep = static_cast<size_t>(0.15 / dt) + 20, iEnd = t.size() - 1;
        // Right after the step the lagged strength still has its slow-sliding (higher) value.
        QVERIFY(lag.contactForce_N[iStep] - plain.contactForce_N[iStep] > 0.05);
        // Long after (15 τ) both agree.
        QVERIFY(std::abs(lag.contactForce_N[iEnd] - plain.contactForce_N[iEnd]) < 1e-3);
    }
    // A vanishing lag gives the model without it at the step the loop uses (1 ms law steps), or
    // a candidate fit could lower its error through the discretisation instead of a lag: with
    // the strength held at its start-of-step value (explicit in α, before session 19) τ = 1e-4 s
    // changed D09's sum of squares at the answer key's parameters by 18 % (551 → 454), and at
    // τ = 1e-6 s the force differed from the bare law's by 0.32 N of 1.51 N.
    void frictionalLagVanishesAsTauGoesToZero() {
        ExtendedModel m = baseModel();
        std::vector<double> t, g;
        const double dt = 1e-3;
        for (double tt = 0; tt < 1.0; tt += dt) { t.push_back(tt); g.push_back(3e-3 * std::sin(2 * M_PI * 2 * tt)); }
        const auto plain = simulateExtendedPrescribed(m, {6.2, 0}, t, g, nullptr, 1);
        double fmax = 0;
        for (double f : plain.contactForce_N) fmax = std::max(fmax, std::abs(f));
        for (double tau : {1e-6, 1e-8}) {
            m.effects.frictionalLag = FrictionalLag{tau};
            const auto lag = simulateExtendedPrescribed(m, {6.2, 0}, t, g, nullptr, 1);
            double worst = 0;
            for (size_t i = 0; i < t.size(); ++i)
                worst = std::max(worst, std::abs(lag.contactForce_N[i] - plain.contactForce_N[i]));
            QVERIFY2(worst < 10 * tau / dt * fmax + 1e-9 * fmax, qPrintable(QString("tau %1: %2 of %3").arg(tau).arg(worst).arg(fmax)));
        }
    }
    void backlashHoldsZeroForceAcrossThePlay() {
        ExtendedModel m = baseModel();
        m.effects.backlash = Backlash{1e-3};
        std::vector<double> t, g;
        const double dt = 1e-4;
        for (double tt = 0; tt < 1.0; tt += dt) { t.push_back(tt); g.push_back(5e-3 * std::sin(2 * M_PI * tt)); }
        const auto tr = simulateExtendedPrescribed(m, {6.2, 0}, t, g, nullptr, 2);
        // After the reversal at t = 0.25 s, g must fall by 2δ before the force turns negative.
        const size_t iRev = static_cast<size_t>(0.25 / dt);
        for (size_t i = iRev; i < t.size(); ++i) {
            if (g[iRev] - g[i] < 1.9e-3) QVERIFY(tr.contactForce_N[i] > -1e-9);
            if (g[iRev] - g[i] > 0.05e-3 && g[iRev] - g[i] < 1.9e-3) QVERIFY(std::abs(tr.contactForce_N[i]) < 1e-9);
        }
        QVERIFY(tr.contactForce_N[static_cast<size_t>(0.5 / dt)] < -1.0);
    }
    void preslidingComplianceSoftensTheLoading() {
        ExtendedModel m = baseModel();
        m.effects.preslidingCompliance = PreslidingCompliance{1e4};
        const ExtendedLaw law = ExtendedLaw::make(m);
        QVERIFY(std::abs(law.epsT() - 1e6 * 1e4 / (1e6 + 1e4)) < 1e-6);
        const auto r = law.returnMap(law.initialState({6.2, 0}), 1e-5, 1e-4, 6.2);
        QVERIFY(r.stuck);
        QVERIFY(std::abs(r.state.force_N - law.epsT() * 1e-5) < 1e-9);
    }
    void outputEffectsAddToTheMeasuredForce() {
        ExtendedModel m = baseModel();
        m.effects.sensorInertia = SensorInertia{0.3};
        m.effects.viscousDamping = ViscousDamping{0.5};
        std::vector<double> t, g;
        for (double tt = 0; tt < 1.0; tt += 1e-3) { t.push_back(tt); g.push_back(2e-3 * std::sin(2 * M_PI * 2 * tt)); }
        const auto tr = simulateExtendedPrescribed(m, {6.2, 0}, t, g, nullptr, 2);
        for (size_t i = 1; i + 1 < t.size(); i += 37) {
            const double expect = tr.contactForce_N[i] + 0.5 * 6.2 * tr.relVel_mps[i] + 0.3 * tr.sliderAccel_mps2[i];
            QVERIFY(std::abs(tr.measuredForce_N[i] - expect) < 1e-9);
        }
    }
    void dynamicsWithoutEffectsMatchesTheCoreStepper() {
        SimParams p;
        p.drive.amplitude_m = 1e-3;
        p.drive.frequency_Hz = 3.0;
        p.integration.dt_s = 1e-4;
        DynamicsModel dm = DynamicsModel::fromParams(p);
        DynState s = dm.initialState(0.0);
        ExtendedModel m = baseModel();
        m.law = p.lawParams<RateStateParams>();
        m.rig = p.rig;
        const long steps = 10000;
        const auto tr = simulateExtendedDynamics(m, {p.rig.normalForce_N, 0}, dm.stage, 0.0, 1e-4, steps, 100);
        QVERIFY(tr.ok());
        std::vector<double> xs;
        advance(dm, s, steps, [&](const DynState& d) { xs.push_back(d.x); });
        QVERIFY(std::abs(tr.slider_m.back() - xs.back()) < 1e-9 + 1e-6 * std::abs(xs.back()));
        // Heavy rig damping changes the response.
        m.effects.viscousDamping = ViscousDamping{0.5};
        const auto damped = simulateExtendedDynamics(m, {p.rig.normalForce_N, 0}, dm.stage, 0.0, 1e-4, steps, 100);
        double a0 = 0, a1 = 0;
        for (size_t i = 50; i < tr.slider_m.size(); ++i) { a0 = std::max(a0, std::abs(tr.slider_m[i])); a1 = std::max(a1, std::abs(damped.slider_m[i])); }
        QVERIFY(std::abs(a0 - a1) > 0.02 * a0);
    }
    void slipPhaseLimitMatchesSteadyState() {
        ExtendedModel m = baseModel();
        std::vector<double> t, V;
        for (double tt = 0; tt < 0.5; tt += 1e-3) { t.push_back(tt); V.push_back(tt < 0.1 ? 0.0 : -0.04); }
        const auto sp = simulateSlipPhaseForce(m, {6.2, 0}, t, V, nullptr, 5e-3);
        QVERIFY(!sp.sliding[50]);
        QVERIFY(sp.sliding.back());
        const RateStateLaw base{m.law};
        QVERIFY(std::abs(sp.force_N.back() / 6.2 + base.steadyStateRatio(0.04)) < 1e-9);
    }
};

QTEST_GUILESS_MAIN(TestEffects)
#include "tst_effects.moc"
