// Energy balance of the coupled scheme (Newmark average acceleration + return mapping):
// over whole forcing cycles the work the stage does through friction equals the energy dissipated
// by slip and by damping plus the change of the stored energy (kinetic, spring, ε_T pre-slip).
#include <QtTest>

#include <cmath>

#include "core/integrate/dynamics.hpp"
#include "physics_helpers.hpp"

using namespace stickslip;
using namespace stickslip::testing;

namespace {

// The discrete identity, step n → n+1 (h = Δt, bars are averages of the two ends):
//
// Newmark average acceleration (β = 1/4, γ = 1/2) gives Δx = h v̄ and Δv = h ā, and the step
// enforces equilibrium at both ends, m a + c v + k x = F, hence m ā + c v̄ + k x̄ = F̄. So
//   ½m(v₁² − v₀²) = m v̄ Δv = m ā Δx,      ½k(x₁² − x₀²) = k x̄ Δx,     c v̄ Δx = c h v̄²,
//   ⇒  F̄ Δx = Δ(½ m v²) + Δ(½ k x²) + c h v̄².                                          (a)
// The return map splits the slip increment Δg = Δu − Δx into elastic and plastic parts,
// F₁ = F₀ + ε_T Δg − s ε_T Δλ (Eq. 4, backward Euler; s = sign F₁), so
//   F̄ Δg = F̄ ΔF/ε_T + s F̄ Δλ = Δ(F²/(2ε_T)) + s F̄ Δλ.                                  (b)
// (a) + (b), with Δu = Δx + Δg:
//   F̄ Δu  =  s F̄ Δλ  +  c h v̄²  +  Δ[½ m v² + ½ k x² + F²/(2ε_T)].
//   (stage work)  (slip)  (damping)   (stored: kinetic + spring + pre-slip)
// Summed over whole cycles this is the balance asked for. It holds for the discrete solution
// exactly, up to the solvers' tolerances (x to ~1e-13 relative, the local residual to
// 1e-13 (|F_tr| + t_N)), so a deviation beyond round-off means the step is not this scheme
// (e.g. equilibrium enforced at one end only, a different β/γ, or a force update that is not
// the return map's).
struct EnergyLedger {
    double stageWork = 0, slipDissipation = 0, dampingDissipation = 0;
    double stagePowerIntegral = 0;  // ∫ F u̇ dt with the exact stage velocity (trapezoid rule)
    double storedStart = 0, storedEnd = 0;
    long slipSteps = 0, negativeSlipSteps = 0;
    double stored(const RigParams& r, double eps, const DynState& s) const {
        return 0.5 * r.mass_kg * s.v * s.v + 0.5 * r.stiffness_N_per_m * s.x * s.x + s.law.force_N * s.law.force_N / (2 * eps);
    }
    double residual() const { return stageWork - (slipDissipation + dampingDissipation + storedEnd - storedStart); }
};

EnergyLedger balance(const SimParams& p, int transientCycles, int cycles) {
    const DynamicsModel m = DynamicsModel::fromParams(p);
    const double eps = std::visit([](const auto& l) { return l.epsT(); }, m.law);
    const double h = m.dt_s;
    DynState s = m.initialState();
    const long perCycle = std::lround(p.drive.period() / h);
    advanceQuiet(m, s, transientCycles * perCycle);
    EnergyLedger e;
    e.storedStart = e.stored(m.rig, eps, s);
    DynState prev = s;
    advance(m, s, cycles * perCycle, [&](const DynState& st) {
        const double Fbar = 0.5 * (prev.law.force_N + st.law.force_N);
        const double vbar = 0.5 * (prev.v + st.v);
        e.stageWork += Fbar * (st.u - prev.u);
        e.stagePowerIntegral += 0.5 * h * (prev.law.force_N * m.stage.velocity(prev.t) + st.law.force_N * m.stage.velocity(st.t));
        e.dampingDissipation += m.rig.damping_Ns_per_m * h * vbar * vbar;
        const double dLambda = st.slipRate * h;
        if (dLambda > 0) {
            const double sgn = st.law.force_N > 0 ? 1.0 : (st.law.force_N < 0 ? -1.0 : (prev.law.force_N >= 0 ? 1.0 : -1.0));
            const double d = sgn * Fbar * dLambda;
            e.slipDissipation += d;
            ++e.slipSteps;
            e.negativeSlipSteps += d < 0 ? 1 : 0;
        }
        prev = st;
    });
    e.storedEnd = e.stored(m.rig, eps, s);
    return e;
}

}  // namespace

class TstEnergy : public QObject {
    Q_OBJECT
private slots:
    void balanceOverWholeCycles_data() {
        QTest::addColumn<bool>("coulomb");
        QTest::addColumn<double>("amplitude");
        QTest::addColumn<double>("epsT");
        QTest::addColumn<double>("zeta");
        QTest::addRow("rate-state A=1mm eps=1e6") << false << 1e-3 << 1e6 << 0.005;
        QTest::addRow("rate-state A=1mm eps=1e6 undamped") << false << 1e-3 << 1e6 << 0.0;
        QTest::addRow("rate-state A=0.4mm eps=1.1e4") << false << 0.4e-3 << 1.1e4 << 0.005;
        QTest::addRow("rate-state A=3mm eps=1e6 zeta=0.05") << false << 3e-3 << 1e6 << 0.05;
        QTest::addRow("coulomb A=1mm eps=1e6") << true << 1e-3 << 1e6 << 0.005;
        QTest::addRow("coulomb A=0.4mm eps=1.1e4") << true << 0.4e-3 << 1.1e4 << 0.005;
    }
    // Over cycles 5–15 (whole forcing cycles after a transient): stage work = slip + damping
    // dissipation + Δ(stored), to 1e-3 relative of the stage work (the bound); and, as the
    // identity above is exact for this scheme, to 1e-8 relative of the largest term as well.
    void balanceOverWholeCycles() {
        QFETCH(bool, coulomb);
        QFETCH(double, amplitude);
        QFETCH(double, epsT);
        QFETCH(double, zeta);
        SimParams p = fig20Params();
        p.law = coulomb ? LawKind::Coulomb : LawKind::RateState;
        p.drive.amplitude_m = amplitude;
        p.lawParams<RateStateParams>().epsT_N_per_m = p.lawParams<CoulombParams>().epsT_N_per_m = epsT;
        p.rig.damping_Ns_per_m = dampingFromRatio(zeta, p.rig.stiffness_N_per_m, p.rig.mass_kg);
        const EnergyLedger e = balance(p, 5, 10);
        const double scale = std::max({std::abs(e.stageWork), e.slipDissipation, e.dampingDissipation,
                                       std::abs(e.storedEnd), std::abs(e.storedStart)});
        qInfo("W_stage = %.9g J, slip %.9g J, damping %.9g J, dE = %.3g J; residual %.3g (%.3g of W)", e.stageWork,
              e.slipDissipation, e.dampingDissipation, e.storedEnd - e.storedStart, e.residual(),
              e.residual() / e.stageWork);
        QVERIFY(e.slipSteps > 0);          // these runs slip
        QVERIFY(e.slipDissipation > 0);    // friction dissipates
        QVERIFY(e.stageWork > 0);          // the stage feeds the motion
        QCOMPARE(e.negativeSlipSteps, 0L); // and dissipates in every slipping step
        if (zeta == 0) QCOMPARE(e.dampingDissipation, 0.0);
        QVERIFY(std::abs(e.residual()) <= 1e-3 * std::abs(e.stageWork));
        // The discrete stage work Σ F̄ Δu is the physical work ∫ F u̇ dt: the two differ by the
        // quadrature error, O((ωh)²) ≈ 4e-7 for smooth F plus O(h) at the kinks of F at the
        // stick–slip switches (F' jumps there); 1e-3 relative is a wide bound for that.
        qInfo("  int F du/dt dt = %.9g J (%.3g relative to the discrete work)", e.stagePowerIntegral,
              e.stagePowerIntegral / e.stageWork - 1);
        QVERIFY(std::abs(e.stagePowerIntegral - e.stageWork) <= 1e-3 * std::abs(e.stageWork));
        QVERIFY2(std::abs(e.residual()) <= 1e-8 * scale, qPrintable(QString("residual %1 of the largest term").arg(e.residual() / scale)));
    }

    // Permanent stick (Coulomb, A below the threshold): no slip dissipation; the stage's work
    // goes into damping and the stored energy only.
    void stickDissipatesNoSlipEnergy() {
        SimParams p = fig20Params();
        p.law = LawKind::Coulomb;
        p.drive.amplitude_m = 0.05e-3;  // force amplitude ≈ 0.41 N < μ t_N = 1.55 N, start transient included
        const EnergyLedger e = balance(p, 5, 10);
        qInfo("stick: W_stage = %.6g J, damping %.6g J, dE = %.3g J", e.stageWork, e.dampingDissipation,
              e.storedEnd - e.storedStart);
        QCOMPARE(e.slipSteps, 0L);
        QCOMPARE(e.slipDissipation, 0.0);
        QVERIFY(e.dampingDissipation > 0);
        const double scale = std::max({std::abs(e.stageWork), e.dampingDissipation, std::abs(e.storedEnd)});
        QVERIFY(std::abs(e.residual()) <= 1e-8 * scale);
    }
};

QTEST_GUILESS_MAIN(TstEnergy)
#include "tst_energy.moc"
