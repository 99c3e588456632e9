// Poincaré section, classification, stick threshold and Lyapunov exponent on the model.
#include <QtTest>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <complex>
#include <numbers>

#include "core/analysis/classify.hpp"
#include "core/analysis/lyapunov.hpp"
#include "core/analysis/poincare.hpp"
#include "core/analysis/section_stepping.hpp"
#include "core/analysis/stick_threshold.hpp"
#include "core/integrate/simulate.hpp"
#include "core/presets.hpp"

using namespace stickslip;
constexpr double kPi = std::numbers::pi;

namespace {
SimParams preset(const char* name) {
    Preset p;
    if (!findPreset(name, p)) qFatal("no preset %s", name);
    return p.params;
}
PoincareSection handMade(const std::vector<double>& x, const std::vector<double>& v, long slipSteps) {
    PoincareSection s;
    s.slider_m = x;
    s.relVel_mps = v;
    s.slipSteps = slipSteps;
    return s;
}
}  // namespace

class TstAnalysisSection : public QObject {
    Q_OBJECT
private slots:
    void sectionSamplesOncePerPeriodAtThePhase() {
        const SimParams p = preset("default");  // A = 1 mm, f = 3 Hz
        PoincareOptions o;
        o.stepsPerPeriod = 2000;
        o.settleCycles = 5;
        o.cycles = 12;
        std::vector<double> progress;
        RunControl ctl;
        ctl.progress = [&](double f) { progress.push_back(f); };
        const PoincareSection s = poincareSection(p, o, ctl);
        QVERIFY2(s.ok(), s.message.c_str());
        QCOMPARE(s.size(), std::size_t(12));
        QCOMPARE(s.ratio.size(), std::size_t(12));
        const double T = 1.0 / 3.0;
        QCOMPARE(s.period_s, T);
        for (std::size_t i = 0; i < s.size(); ++i) QVERIFY(std::abs(s.t_s[i] - (5 + i + 1) * T) < 1e-9);
        QVERIFY(s.stickFraction > 0 && s.stickFraction < 1);
        QVERIFY(s.slipSteps > 0);
        QVERIFY(s.maxRelVel_mps > 0);
        for (double V : s.relVel_mps) QVERIFY(std::abs(V) <= s.maxRelVel_mps);
        for (double r : s.ratio) QVERIFY(std::abs(r) < 0.6);
        QVERIFY(!progress.empty());
        for (std::size_t i = 1; i < progress.size(); ++i) QVERIFY(progress[i] >= progress[i - 1]);
        QCOMPARE(progress.back(), 1.0);
        // Phase π/2: a quarter period later.
        o.phase_rad = kPi / 2;
        const PoincareSection q = poincareSection(p, o);
        QVERIFY(q.ok());
        QVERIFY(std::abs(q.t_s[0] - (6.25) * T) < 1e-9);
        QCOMPARE(stepsPerPeriodFor(p, 0), 10000L);  // default dt = T/10 000 at 3 Hz
        QCOMPARE(stepsPerPeriodFor(p, 123), 123L);
        QCOMPARE(poincareModel(p, 1000).dt_s, T / 1000);
    }
    // The phase-0 section a run records (RunResult::period, read by sectionOfRun) equals
    // poincareSection with the same step, settle = transient and cycles: the same steps, so the
    // same points up to round-off (the stage phase is re-anchored at other steps), and the same
    // stick/slip counts and max |V|.
    void sectionOfRunEqualsPoincareSection() {
        for (const char* name : {"fig20", "fig23"}) {
            SimParams p = preset(name);
            p.integration.dt_s = p.drive.period() / 4000.0;
            for (double transient : {0.0, 3.0}) {
                p.transientCycles = transient;
                p.cycles = 7;
                const RunResult run = simulate(p);
                QVERIFY2(run.ok(), run.message.c_str());
                QCOMPARE(run.period.stepsPerPeriod, 4000L);
                PoincareOptions o;
                o.settleCycles = static_cast<long>(transient);
                o.cycles = 7;
                const PoincareSection ref = poincareSection(p, o);
                QVERIFY2(ref.ok(), ref.message.c_str());
                const PoincareSection sec = sectionOfRun(run, p.drive.period());
                QVERIFY2(sec.ok(), sec.message.c_str());
                QCOMPARE(sec.size(), ref.size());
                QCOMPARE(sec.size(), std::size_t(7));
                double xScale = 0, vScale = 0;
                for (const Sample& s : run.samples) {
                    xScale = std::max(xScale, std::abs(s.slider_m));
                    vScale = std::max(vScale, std::abs(s.relVel_mps));
                }
                for (std::size_t i = 0; i < sec.size(); ++i) {
                    QVERIFY(std::abs(sec.t_s[i] - ref.t_s[i]) <= 1e-12 * ref.t_s[i]);
                    QVERIFY2(std::abs(sec.slider_m[i] - ref.slider_m[i]) <= 1e-9 * xScale,
                             qPrintable(QString("%1 point %2: x %3 vs %4").arg(name).arg(i)
                                            .arg(sec.slider_m[i], 0, 'g', 17).arg(ref.slider_m[i], 0, 'g', 17)));
                    QVERIFY(std::abs(sec.relVel_mps[i] - ref.relVel_mps[i]) <= 1e-9 * vScale);
                    QVERIFY(std::abs(sec.ratio[i] - ref.ratio[i]) <= 1e-9);
                    QVERIFY(std::abs(sec.alpha[i] - ref.alpha[i]) <= 1e-9 * (1 + std::abs(ref.alpha[i])));
                }
                // Stuck/slip decisions can only flip on a step within round-off of the slip threshold.
                QVERIFY(std::abs(sec.slipSteps - ref.slipSteps) <= 2);
                QVERIFY(std::abs(sec.stickFraction - ref.stickFraction) <= 1e-4);
                QVERIFY(sec.slipSteps > 0);
                QVERIFY(std::abs(sec.maxRelVel_mps - ref.maxRelVel_mps) <= 1e-9 * ref.maxRelVel_mps);
            }
        }
        // No section when the step does not divide the period, nor for prescribed slip.
        SimParams p = preset("fig20");
        p.integration.dt_s = p.drive.period() / 4000.5;
        p.cycles = 2;
        const RunResult odd = simulate(p);
        QVERIFY(odd.ok());
        QCOMPARE(odd.period.stepsPerPeriod, 0L);
        QVERIFY(odd.period.samples.empty());
        const PoincareSection none = sectionOfRun(odd, p.drive.period());
        QVERIFY(!none.ok());
        QVERIFY(none.message.find("dt does not divide") != std::string::npos);
        QCOMPARE(stepsPerPeriodDividing(p), 0L);
        const RunResult block = simulate(preset("fig16"));
        QVERIFY(block.ok());
        QCOMPARE(block.period.stepsPerPeriod, 0L);
    }
    // The motion measures of advanceSampledCycle (max |V| over every step, stuck/slip step
    // counts) against a brute-force pass over the same steps with the exact stage velocity.
    void sampledCycleMeasuresMatchBruteForce() {
        const SimParams p = preset("fig20");  // slips and sticks at A = 1 mm
        const long n = 3000;                   // > 256: the velocity recurrence is re-anchored
        const DynamicsModel m = poincareModel(p, n);
        DynState s = m.initialState(0.0);
        QVERIFY(detail::settleCycles(m, s, n, 5, {}).status == RunStatus::Ok);
        DynState ref = s;
        double vmax = 0;
        long stuck = 0, steps = 0;
        for (int c = 0; c < 3; ++c) {  // cycle by cycle, as advanceSampledCycle steps
            const StepReport r0 = advance(m, ref, n, [&](const DynState& st) {
                vmax = std::max(vmax, std::abs(m.stage.velocity(st.t) - st.v));
                stuck += st.stuck ? 1 : 0;
                ++steps;
            });
            QVERIFY(r0.status == RunStatus::Ok);
        }
        QVERIFY(stuck > 0 && stuck < steps);
        PoincareSection sec;
        long stuckOut = 0;
        for (int c = 0; c < 3; ++c)
            QVERIFY(detail::advanceSampledCycle(m, s, n, sec, stuckOut, {}).status == RunStatus::Ok);
        QCOMPARE(sec.size(), std::size_t(3));
        QCOMPARE(stuckOut, stuck);
        QCOMPARE(sec.slipSteps, steps - stuck);
        QCOMPARE(s.x, ref.x);  // observing does not change the run
        QVERIFY2(std::abs(sec.maxRelVel_mps - vmax) <= 1e-12 * vmax,
                 qPrintable(QString("%1 vs %2").arg(sec.maxRelVel_mps, 0, 'g', 17).arg(vmax, 0, 'g', 17)));
    }
    // phaseOffsetSteps = round(phase/2π · n) mod n, into [0, n): a whole turn is no offset,
    // a phase that rounds up to n steps wraps to 0, negative phases count back from n.
    void phaseOffsetStepsRoundsModN() {
        using detail::phaseOffsetSteps;
        QCOMPARE(phaseOffsetSteps(0.0, 100), 0L);
        QCOMPARE(phaseOffsetSteps(kPi / 2, 100), 25L);
        QCOMPARE(phaseOffsetSteps(kPi, 100), 50L);
        QCOMPARE(phaseOffsetSteps(2 * kPi * 0.994, 100), 99L);   // 99.4 → 99
        QCOMPARE(phaseOffsetSteps(2 * kPi * 0.996, 100), 0L);    // 99.6 → 100 ≡ 0
        QCOMPARE(phaseOffsetSteps(2 * kPi * 0.0049, 100), 0L);   // 0.49 → 0
        QCOMPARE(phaseOffsetSteps(2 * kPi * 0.0051, 100), 1L);   // 0.51 → 1
        QCOMPARE(phaseOffsetSteps(2 * kPi, 100), 0L);
        QCOMPARE(phaseOffsetSteps(4 * kPi + kPi / 2, 100), 25L);
        QCOMPARE(phaseOffsetSteps(-kPi / 2, 100), 75L);
        QCOMPARE(phaseOffsetSteps(-2 * kPi, 100), 0L);
        QCOMPARE(phaseOffsetSteps(-2 * kPi * 0.996, 100), 0L);  // −99.6 → −100 ≡ 0
        QCOMPARE(phaseOffsetSteps(kPi / 3, 10000), 1667L);       // 1666.67
        QCOMPARE(phaseOffsetSteps(kPi, 7), 4L);                  // 3.5 rounds away from zero
        for (double phase : {0.0, 1.0, 3.0, 6.0, -1.0})
            QCOMPARE(phaseOffsetSteps(phase, 1), 0L);
        // A section phase just below 2π samples on the cycle boundary, as phase 0 does: the
        // first point one period after the settled cycles, not two.
        PoincareOptions o;
        o.stepsPerPeriod = 200;
        o.settleCycles = 0;
        o.cycles = 2;
        o.phase_rad = 2 * kPi - 1e-3;  // 199.97 steps → 200 ≡ 0
        const PoincareSection sec = poincareSection(preset("default"), o);
        QVERIFY2(sec.ok(), sec.message.c_str());
        const double T = 1.0 / 3.0;
        QVERIFY(std::abs(sec.t_s[0] - T) < 1e-9);
        QVERIFY(std::abs(sec.t_s[1] - 2 * T) < 1e-9);
    }

    // appendSectionPoint appends (t, x, V = u̇(t) − ẋ, F/t_N, α) of the state and touches
    // nothing else; u̇ is the model's stage velocity A ω cos(ωt + φ).
    void appendSectionPointRecordsTheState() {
        SimParams p = preset("default");
        p.drive.phase_rad = 0.3;
        p.rig.normalForce_N = 4.0;
        const DynamicsModel m = DynamicsModel::fromParams(p);
        DynState s;
        s.t = 0.7;
        s.x = 2.5e-4;
        s.v = -0.01;
        s.law.force_N = -1.2;
        s.law.alpha = 0.35;
        PoincareSection out;
        detail::appendSectionPoint(m, s, out);
        DynState s2 = s;
        s2.t = 1.1;
        s2.x = -1e-4;
        detail::appendSectionPoint(m, s2, out);
        QCOMPARE(out.size(), std::size_t(2));
        QCOMPARE(out.t_s, (std::vector<double>{0.7, 1.1}));
        QCOMPARE(out.slider_m, (std::vector<double>{2.5e-4, -1e-4}));
        QCOMPARE(out.ratio, (std::vector<double>{-0.3, -0.3}));
        QCOMPARE(out.alpha, (std::vector<double>{0.35, 0.35}));
        QCOMPARE(out.relVel_mps.size(), std::size_t(2));
        const double w = 2 * kPi * 3.0;
        for (std::size_t i = 0; i < 2; ++i) {
            const double V = 1e-3 * w * std::cos(w * out.t_s[i] + 0.3) + 0.01;
            QVERIFY2(std::abs(out.relVel_mps[i] - V) <= 1e-14, qPrintable(QString::number(out.relVel_mps[i] - V)));
        }
        QCOMPARE(out.slipSteps, 0L);
        QCOMPARE(out.stickFraction, 0.0);
        QCOMPARE(out.maxRelVel_mps, 0.0);
        QVERIFY(out.ok());
    }

    // poincareSectionFrom from a prepared model and state: settle, then one point per period at
    // t = (settle + k) T, each the state after k more periods of the same steps (brute force,
    // cycle by cycle as the section steps), stick fraction = stuck / sampled steps, s left at
    // the last point so that a second call continues the first; progress rises to 1; a cancel
    // stops it with status Cancelled.
    void poincareSectionFromContinuesAPreparedState() {
        const SimParams p = preset("fig20");  // sticks and slips at A = 1 mm
        const long n = 1000;
        const DynamicsModel m = poincareModel(p, n);
        const double T = p.drive.period();
        DynState s = m.initialState(0.0);
        std::vector<double> progress;
        RunControl ctl;
        ctl.progress = [&](double f) { progress.push_back(f); };
        const PoincareSection a = poincareSectionFrom(m, s, n, 3, 4, ctl);
        QVERIFY2(a.ok(), a.message.c_str());
        QCOMPARE(a.size(), std::size_t(4));
        QVERIFY(std::abs(a.period_s - T) <= 1e-15 * T);
        QCOMPARE(progress.size(), std::size_t(7));
        QVERIFY(std::is_sorted(progress.begin(), progress.end()) && progress.back() == 1.0);
        DynState ref = m.initialState(0.0);
        for (int c = 0; c < 3; ++c) advanceQuiet(m, ref, n);
        long stuck = 0;
        double vmax = 0;
        for (std::size_t k = 0; k < 4; ++k) {
            advance(m, ref, n, [&](const DynState& st) {
                stuck += st.stuck ? 1 : 0;
                vmax = std::max(vmax, std::abs(m.stage.velocity(st.t) - st.v));
            });
            QVERIFY(std::abs(a.t_s[k] - double(3 + k + 1) * T) < 1e-9);
            QCOMPARE(a.slider_m[k], ref.x);
            QCOMPARE(a.ratio[k], ref.law.force_N / p.rig.normalForce_N);
            QCOMPARE(a.alpha[k], ref.law.alpha);
            QVERIFY(std::abs(a.relVel_mps[k] - (m.stage.velocity(ref.t) - ref.v)) <= 1e-12);
        }
        QVERIFY(stuck > 0 && stuck < 4 * n);
        QCOMPARE(a.slipSteps, 4 * n - stuck);
        QCOMPARE(a.stickFraction, double(stuck) / double(4 * n));
        QVERIFY(std::abs(a.maxRelVel_mps - vmax) <= 1e-12 * vmax);
        QCOMPARE(s.t, a.t_s.back());
        QCOMPARE(s.x, a.slider_m.back());
        // Continuing from s: the next points of one longer section.
        const PoincareSection b = poincareSectionFrom(m, s, n, 0, 2);
        DynState s2 = m.initialState(0.0);
        const PoincareSection whole = poincareSectionFrom(m, s2, n, 3, 6);
        QVERIFY(b.ok() && whole.ok());
        for (std::size_t k = 0; k < 2; ++k) {
            QVERIFY(std::abs(b.t_s[k] - whole.t_s[4 + k]) < 1e-9);
            QCOMPARE(b.slider_m[k], whole.slider_m[4 + k]);
        }
        std::atomic<bool> cancel{true};
        RunControl stop;
        stop.cancel = &cancel;
        DynState s3 = m.initialState(0.0);
        const PoincareSection c = poincareSectionFrom(m, s3, n, 2, 2, stop);
        QVERIFY(c.status == RunStatus::Cancelled);
        QCOMPARE(c.message, std::string("cancelled"));
        QCOMPARE(c.size(), std::size_t(0));
    }

    // poincareSectionAdaptive on a period-1 orbit (Fig. 20 set, A = 1 mm) samples at exactly
    // s.t + (settle + k) T and agrees with the fixed-step section. The fixed step (Newmark with
    // the backward-Euler return map) is first order while slipping (adaptive.hpp: e = c1 h + …),
    // so its section moves toward the adaptive one as N grows (seen: x off by 3.7e-3 A at
    // N = 10 000, 9.8e-4 A at 40 000, 2.5e-4 A at 160 000) and the extrapolation
    // x_4N + (x_4N − x_N)/3 of N = 40 000 and 160 000 meets it to the tolerance, 1e-5 (seen:
    // 4.7e-6 A in x, 9.7e-6 A ω in V, 1.2e-6 in F/t_N); the bounds allow 5e-5.
    void adaptiveSectionAgreesWithFixedStep() {
        const SimParams p = preset("fig20");
        const double T = p.drive.period(), A = p.drive.amplitude_m, vScale = A * p.drive.omega();
        const long settle = 20, cycles = 3;
        auto fixedSection = [&](long n) {
            const DynamicsModel fm = poincareModel(p, n);
            DynState fs = fm.initialState(0.0);
            return poincareSectionFrom(fm, fs, n, settle, cycles);
        };
        const PoincareSection coarse = fixedSection(40000), fine = fixedSection(160000);
        QVERIFY(coarse.ok() && fine.ok());
        AdaptiveOptions o;
        o.tolerance = 1e-5;
        const DynamicsModel am = DynamicsModel::fromParams(p);
        DynState as = am.initialState(0.0);
        const PoincareSection ad = poincareSectionAdaptive(am, as, T, settle, cycles, o);
        QVERIFY2(ad.ok(), ad.message.c_str());
        QCOMPARE(ad.size(), std::size_t(cycles));
        QCOMPARE(ad.period_s, T);
        QVERIFY(std::abs(as.t - double(settle + cycles) * T) <= 1e-12);
        double errX = 0, errV = 0, errR = 0, offCoarse = 0, offFine = 0;
        auto extrapolated = [&](const std::vector<double>& c, const std::vector<double>& f, std::size_t k) {
            return f[k] + (f[k] - c[k]) / 3;
        };
        for (std::size_t k = 0; k < ad.size(); ++k) {
            QVERIFY(std::abs(ad.t_s[k] - double(settle + long(k) + 1) * T) <= 1e-12);
            errX = std::max(errX, std::abs(ad.slider_m[k] - extrapolated(coarse.slider_m, fine.slider_m, k)));
            errV = std::max(errV, std::abs(ad.relVel_mps[k] - extrapolated(coarse.relVel_mps, fine.relVel_mps, k)));
            errR = std::max(errR, std::abs(ad.ratio[k] - extrapolated(coarse.ratio, fine.ratio, k)));
            offCoarse = std::max(offCoarse, std::abs(ad.slider_m[k] - coarse.slider_m[k]));
            offFine = std::max(offFine, std::abs(ad.slider_m[k] - fine.slider_m[k]));
        }
        qInfo("adaptive vs fixed: x off %.3g A (N = 40 000), %.3g A (160 000), extrapolated: |dx| = %.3g A, "
              "|dV| = %.3g A w, |dF/tN| = %.3g; stick %.4f vs %.4f, max|V| %.6g vs %.6g", offCoarse / A, offFine / A,
              errX / A, errV / vScale, errR, ad.stickFraction, fine.stickFraction, ad.maxRelVel_mps, fine.maxRelVel_mps);
        QVERIFY(offFine < 0.5 * offCoarse);  // the fixed section converges toward the adaptive one
        QVERIFY(errX <= 5e-5 * A);
        QVERIFY(errV <= 5e-5 * vScale);
        QVERIFY(errR <= 5e-5);
        QVERIFY(std::abs(ad.stickFraction - fine.stickFraction) <= 2e-3);
        QVERIFY(std::abs(ad.maxRelVel_mps - fine.maxRelVel_mps) <= 1e-2 * fine.maxRelVel_mps);
        QVERIFY(ad.slipSteps > 0);
    }

    void sectionReportsBadInputAndCancel() {
        SimParams p = preset("default");
        p.rig.normalForce_N = -1;
        PoincareOptions o;
        o.cycles = 0;
        const PoincareSection s = poincareSection(p, o);
        QVERIFY(s.status == RunStatus::Failed);
        QVERIFY(s.message.find("tN") != std::string::npos);
        QVERIFY(s.message.find("cycles") != std::string::npos);
        std::atomic<bool> cancel{true};
        RunControl ctl;
        ctl.cancel = &cancel;
        PoincareOptions ok;
        ok.stepsPerPeriod = 10000;
        const PoincareSection c = poincareSection(preset("default"), ok, ctl);
        QVERIFY(c.status == RunStatus::Cancelled);
    }
    void stickThresholdMatchesClosedFormAndSimulation() {
        for (LawKind law : {LawKind::RateState, LawKind::Coulomb}) {
            SimParams p = preset("fig20");  // ε_T = 1.1e4 N/m
            p.law = law;
            const double w = 2 * kPi * p.drive.frequency_Hz;
            const double Z = std::abs(std::complex<double>(p.rig.stiffness_N_per_m - p.rig.mass_kg * w * w,
                                                           p.rig.damping_Ns_per_m * w));
            const double closed = 0.25 * 6.2 * (1 / Z + 1 / 1.1e4);
            const double As = stickThresholdAmplitude(p);
            QVERIFY2(std::abs(As - closed) < 1e-6 * closed, qPrintable(QString::number(As)));
            QVERIFY(As > 0.32e-3 && As < 0.34e-3);  // the paper's 0.33 mm
            PoincareOptions o;
            o.stepsPerPeriod = 2000;
            o.settleCycles = 40;
            o.cycles = 10;
            setParam(p, "A", 0.9 * As);
            const PoincareSection below = poincareSection(p, o);
            QVERIFY(below.ok());
            QVERIFY(classifyMotion(below, classifyScales(p)).motion == MotionClass::Stick);
            setParam(p, "A", 1.1 * As);
            const PoincareSection above = poincareSection(p, o);
            QVERIFY(above.ok());
            QVERIFY(above.slipSteps > 0);
            QVERIFY(classifyMotion(above, classifyScales(p)).motion != MotionClass::Stick);
        }
    }
    void classificationWithStatedTolerance() {
        const ClassifyScales sc{1e-3, 1e-2};
        ClassifyOptions o;  // relTol 1e-4: 1e-7 m, 1e-6 m/s
        std::vector<double> x, v;
        for (int i = 0; i < 48; ++i) {
            x.push_back(1e-4 * (i % 3));
            v.push_back(1e-3 * ((i % 3) == 1));
        }
        Classification c = classifyMotion(handMade(x, v, 10), sc, o);
        QVERIFY(c.motion == MotionClass::Periodic);
        QCOMPARE(c.period, 3);
        // Within tolerance (0.5 relTol) still period 3; beyond (3 relTol) not periodic ≤ 16.
        auto xn = x;
        for (std::size_t i = 0; i < xn.size(); i += 2) xn[i] += 0.5e-7;
        QCOMPARE(classifyMotion(handMade(xn, v, 10), sc, o).period, 3);
        for (std::size_t i = 0; i < xn.size(); i += 2) xn[i] += 3e-7;
        c = classifyMotion(handMade(xn, v, 10), sc, o);
        QVERIFY(c.motion == MotionClass::Periodic);  // the perturbation itself has period 2·3 = 6
        QCOMPARE(c.period, 6);
        std::vector<double> irr;
        double z = 0.3;
        for (int i = 0; i < 48; ++i) { z = 3.9 * z * (1 - z); irr.push_back(1e-3 * z); }
        c = classifyMotion(handMade(irr, v, 10), sc, o);
        QVERIFY(c.motion == MotionClass::Irregular);
        QCOMPARE(c.period, 0);
        QVERIFY(c.bestMismatch > 1);
        c = classifyMotion(handMade(x, v, 0), sc, o);
        QVERIFY(c.motion == MotionClass::Stick);
        QCOMPARE(QString(toString(MotionClass::Irregular)), QString("irregular"));
        ClassifyOptions bad;
        bad.maxPeriod = 0;
        bad.relTol = 2;
        QCOMPARE(bad.validate().size(), std::size_t(2));
        const ClassifyScales s = classifyScales(preset("default"));
        QCOMPARE(s.x_m, 1e-3);
        QVERIFY(std::abs(s.v_mps - 1e-3 * 2 * kPi * 3) < 1e-12);
    }
    void separationHelpers() {
        const SimParams p = preset("default");
        const SeparationScales sc = separationScales(p);
        QVERIFY(std::abs(sc.x_m - 0.25 * 6.2 / 8446) < 1e-12);
        QVERIFY(std::abs(sc.force_N - 1.55) < 1e-12);
        DynState s;
        s.x = 1e-4; s.v = 0.01; s.law.force_N = 0.3; s.law.alpha = -0.2;
        DynState q = perturbedState(s, p.rig, sc, 1e-6);
        QVERIFY(std::abs(stateSeparation(s, q, sc) - 1e-6) < 1e-12);
        // Newmark consistency: m δa + c δv + k δx = 0.
        QVERIFY(std::abs(p.rig.mass_kg * (q.a - s.a) + p.rig.damping_Ns_per_m * (q.v - s.v) +
                         p.rig.stiffness_N_per_m * (q.x - s.x)) < 1e-12);
        q.law.force_N += 1e-3;
        const double before = stateSeparation(s, q, sc);
        QCOMPARE(renormalise(s, q, sc, 1e-7), before);
        QVERIFY(std::abs(stateSeparation(s, q, sc) - 1e-7) < 1e-13);
    }
    // The companion trajectory on its own thread: the same exponent, growth and section, bit for bit.
    void lyapunovCompanionThreadGivesTheSameResult() {
        const SimParams p = preset("fig20");
        const long n = 1000;
        const DynamicsModel m = poincareModel(p, n);
        DynState s = m.initialState(0.0);
        QVERIFY(detail::settleCycles(m, s, n, 10, {}).status == RunStatus::Ok);
        DynState a = s, b = s;
        PoincareSection sa, sb;
        const LyapunovResult ra = largestLyapunovFrom(m, a, n, 12, 1e-7, separationScales(p), {}, &sa, false);
        const LyapunovResult rb = largestLyapunovFrom(m, b, n, 12, 1e-7, separationScales(p), {}, &sb, true);
        QVERIFY(ra.ok() && rb.ok());
        QCOMPARE(rb.logGrowth.size(), std::size_t(12));
        QVERIFY(ra.logGrowth == rb.logGrowth);
        QCOMPARE(ra.perCycle, rb.perCycle);
        QVERIFY(sa.slider_m == sb.slider_m && sa.relVel_mps == sb.relVel_mps);
        QCOMPARE(sa.stickFraction, sb.stickFraction);
        QCOMPARE(a.x, b.x);
        // Cancelled from the start: both stop with the same status.
        std::atomic<bool> cancel{true};
        RunControl stop;
        stop.cancel = &cancel;
        DynState c = s;
        const LyapunovResult rc = largestLyapunovFrom(m, c, n, 12, 1e-7, separationScales(p), stop, nullptr, true);
        QVERIFY(rc.status == RunStatus::Cancelled);
    }
    void lyapunovNegativeOnAPeriodOneOrbit() {
        const SimParams p = preset("default");  // A = 1 mm, ε_T = 1e6: period-1
        LyapunovOptions o;
        o.stepsPerPeriod = 2000;
        o.settleCycles = 30;
        o.cycles = 30;
        const LyapunovResult r = largestLyapunov(p, o);
        QVERIFY2(r.ok(), r.message.c_str());
        QCOMPARE(r.logGrowth.size(), std::size_t(30));
        QVERIFY2(r.perCycle < -0.05, qPrintable(QString::number(r.perCycle)));
        QVERIFY(std::abs(r.perSecond - r.perCycle * 3.0) < 1e-9);
        LyapunovOptions bad;
        bad.cycles = 0;
        bad.d0 = 0;
        const LyapunovResult b = largestLyapunov(p, bad);
        QVERIFY(b.status == RunStatus::Failed);
        QVERIFY(b.message.find("d0") != std::string::npos);
    }
};

QTEST_GUILESS_MAIN(TstAnalysisSection)
#include "tst_analysis_section.moc"
