// The Dieterich–Ruina law (core/friction/dieterich_ruina.*) against its closed forms: steady
// state, the velocity-step response of the aging law, the consistent tangent, and the law
// going through every path a registered law must (parameter keys, simulate in both set-ups,
// sweep, fit).
#include <QtTest>

#include <cmath>

#include "core/analysis/sweep.hpp"
#include "core/friction/friction_law.hpp"
#include "core/identify/fit.hpp"
#include "core/integrate/simulate.hpp"
#include "core/params.hpp"
#include "core/presets.hpp"
#include "physics_helpers.hpp"

using namespace stickslip;
using stickslip::testing::fig20Params;

namespace {

DieterichRuinaLaw law(double epsT = 1e9) {
    DieterichRuinaParams p;  // μ0 0.25, a 0.01, b 0.015, L 20 µm, V0 1 mm/s
    p.epsT_N_per_m = epsT;
    return DieterichRuinaLaw{p};
}

// The closed forms, written independently of the law's code.
double ssRatio(const DieterichRuinaParams& p, double V) {
    return p.a * std::asinh(V / (2 * p.V0_mps) * std::exp((p.mu + p.b * std::log(p.V0_mps / V)) / p.a));
}
double ratioAt(const DieterichRuinaParams& p, double V, double theta) {
    return p.a * std::asinh(V / (2 * p.V0_mps) * std::exp((p.mu + p.b * std::log(p.V0_mps * theta / p.Dc_m)) / p.a));
}

LawState slide(const DieterichRuinaLaw& l, LawState s, double V, double dt, long steps, double tN) {
    for (long i = 0; i < steps; ++i) s = l.returnMap(s, V * dt, dt, tN).state;
    return s;
}

}  // namespace

class TstDieterichRuina : public QObject {
    Q_OBJECT
private slots:
    // Steady sliding: backward Euler has the exact fixed point Δλ = VΔt, θ = L/V, so the force
    // after the transient equals the closed form to the local solver's tolerance; and for
    // V ≫ V0 e^{-μ0/a} the regularised form is μ0 + (a − b) ln(V/V0).
    void steadyState_data() {
        QTest::addColumn<double>("V");
        for (double V : {1e-5, 1e-4, 1e-3, 1e-2, 0.1}) QTest::addRow("V=%g", V) << V;
    }
    void steadyState() {
        QFETCH(double, V);
        const DieterichRuinaLaw l = law();
        const double tN = 6.2, dt = 0.1 * l.params.Dc_m / V;  // Δλ = L/10 per step
        const LawState s = slide(l, LawState{}, V, dt, 4000, tN);
        const double ratio = s.force_N / tN;
        QVERIFY2(std::abs(ratio - ssRatio(l.params, V)) < 1e-9, qPrintable(QString::number(ratio - ssRatio(l.params, V))));
        QVERIFY(std::abs(l.steadyStateRatio(V) - ssRatio(l.params, V)) < 1e-14);
        QVERIFY(std::abs(s.alpha - std::log(l.params.V0_mps / V)) < 1e-8);
        const double logForm = l.params.mu + (l.params.a - l.params.b) * std::log(V / l.params.V0_mps);
        QVERIFY(std::abs(ratio - logForm) < 1e-8);
    }

    // A velocity step V1 → V2 at steady state: with a stiff contact (ε_T = 1e9 N/m, elastic
    // length ~1e-10 m ≪ L) the slip rate follows the step at once and θ obeys the aging law at
    // constant V2: θ(t) = L/V2 + (L/V1 − L/V2) e^{−V2 t/L}, μ(t) = a asinh(V2/(2V0) e^{(μ0 + b ln(V0 θ/L))/a}).
    // The direct effect a ln(V2/V1) and the new steady state (a − b) ln(V2/V1) follow.
    void velocityStep() {
        const DieterichRuinaLaw l = law();
        const DieterichRuinaParams& p = l.params;
        const double tN = 6.2, V1 = 1e-3, V2 = 1e-2;
        const double dt = 1e-3 * p.Dc_m / V2;  // Δλ = L/1000 per step after the step
        LawState s = slide(l, LawState{}, V1, 0.1 * p.Dc_m / V1, 4000, tN);
        const double mu1 = s.force_N / tN;
        double peak = mu1, maxErr = 0;
        for (long i = 1; i <= 10000; ++i) {  // 10 L of slip
            s = l.returnMap(s, V2 * dt, dt, tN).state;
            const double t = i * dt;
            peak = std::max(peak, s.force_N / tN);
            if (t * V2 < 0.05 * p.Dc_m) continue;  // the first 1/20 L: the elastic and BE start-up
            const double theta = p.Dc_m / V2 + (p.Dc_m / V1 - p.Dc_m / V2) * std::exp(-V2 * t / p.Dc_m);
            maxErr = std::max(maxErr, std::abs(s.force_N / tN - ratioAt(p, V2, theta)));
        }
        // BE on θ with Δλ = L/1000: a relative lag ~5e-4 in the decay, b·5e-4·ln10 ≈ 2e-5 in μ.
        QVERIFY2(maxErr < 5e-5, qPrintable(QString::number(maxErr)));
        QVERIFY(std::abs((peak - mu1) - p.a * std::log(V2 / V1)) < 0.02 * p.a * std::log(V2 / V1));
        // After 10 L, e^-10 of the θ transient is left: b (V2/V1) e^-10 ≈ 7e-6 in μ.
        QVERIFY(std::abs((s.force_N / tN - mu1) - (p.a - p.b) * std::log(V2 / V1)) < 1e-5);
    }

    // The consistent tangent equals dF/dΔg by central differences, in creep and in slip, and
    // healing at rest raises the strength by b ln((θ + Δt)/θ).
    void tangentAndHealing() {
        const DieterichRuinaLaw l = law(1e6);
        const double tN = 6.2, dt = 1e-4;
        for (double V : {1e-6, 1e-4, 1e-2, 0.1}) {
            LawState s = slide(l, LawState{}, V, 0.1 * l.params.Dc_m / V, 4000, tN);
            const double dg = V * dt, h = 1e-6 * std::max(dg, 1e-12);
            const ReturnMapResult r = l.returnMap(s, dg, dt, tN);
            QVERIFY(r.converged);
            const double fd = (l.returnMap(s, dg + h, dt, tN).state.force_N - l.returnMap(s, dg - h, dt, tN).state.force_N) / (2 * h);
            QVERIFY2(std::abs(fd - r.tangent_N_per_m) < 1e-5 * l.params.epsT_N_per_m,
                     qPrintable(QString("V=%1: fd %2 tangent %3").arg(V).arg(fd).arg(r.tangent_N_per_m)));
        }
        // At rest with F = 0 no slip happens and θ grows by Δt.
        LawState s;
        const ReturnMapResult r = l.returnMap(s, 0.0, 1.0, tN);
        const double theta0 = l.params.Dc_m / l.params.V0_mps;
        QVERIFY(r.stuck);
        QVERIFY(std::abs(r.state.alpha - std::log((theta0 + 1.0) / theta0)) < 1e-12);
    }

    // A registered law in every path: --model name, parameter keys, validation naming the key,
    // simulate in both set-ups, a continuation sweep (the fit: tst_cli_fit).
    void throughEveryPath() {
        LawKind k;
        QVERIFY(parseLawKind("dieterich-ruina", k));
        QCOMPARE(std::string(toString(k)), std::string("dieterich-ruina"));
        QVERIFY(lawHasParam(k, "a") && lawHasParam(k, "b") && lawHasParam(k, "V0") && lawHasParam(k, "Dc"));
        SimParams p = fig20Params();
        p.law = k;
        QVERIFY(setParam(p, "a", 0.02));
        QCOMPARE(p.lawParams<DieterichRuinaParams>().a, 0.02);
        QVERIFY(setParam(p, "a", -1));
        const ParamIssues bad = p.validate();
        QVERIFY(bad.size() == 1 && bad[0].field == "a");
        QVERIFY(setParam(p, "a", 0.01));
        p.cycles = 5;
        for (SetupKind setup : {SetupKind::Dynamics, SetupKind::Prescribed}) {
            p.setup = setup;
            const RunResult r = simulate(p);
            QVERIFY2(r.status == RunStatus::Ok, r.message.c_str());
            QVERIFY(!r.samples.empty());
            bool stuck = false, slipping = false;
            for (const Sample& x : r.samples) (x.stuck ? stuck : slipping) = true;
            QVERIFY(stuck && slipping);  // A = 1 mm at 3 Hz: stick at reversals, slip between
        }
        p.setup = SetupKind::Dynamics;
        SweepOptions so;
        so.from = 0.2e-3;
        so.to = 1e-3;
        so.steps = 3;
        so.settleCycles = 5;
        so.sampleCycles = 5;
        QVERIFY(so.validate(p).empty());
        const SweepResult sr = bifurcationSweep(p, so);
        QCOMPARE(sr.points.size(), size_t(3));
    }
};

QTEST_APPLESS_MAIN(TstDieterichRuina)
#include "tst_dieterich_ruina.moc"
