// The check of the law channel's time resolution (law_resolution.cpp, identify.hpp LawResolution):
// a soft contact that is unstable under its own law must be reported unresolved at the fits'
// step, a stiff stable one resolved; the refined law run converges to the fine reference.
#include <QtTest/QtTest>

#include <cmath>
#include <random>

#include "core/identify/identify_internal.hpp"

using namespace stickslip;
using namespace stickslip::identify;
using namespace stickslip::identify::detail;

namespace {

// The law of seed 304 of `synthesize` (docs/identify-results.md, session 48): ε_T below the
// contact's critical stiffness t_N (C1 C2 e^{-C2 V} − η) V / D_c over a band of slip rates.
ExtendedModel softUnstableContact() {
    ExtendedModel m;
    m.law.mu = 0.288;
    m.law.C1 = 0.253;
    m.law.r = 1.0;
    m.law.Dc_m = 1.75e-5;
    m.law.eta_s_per_m = 0.314;
    m.law.vc_mps = 0.0687;
    m.law.epsT_N_per_m = 12900.0;
    return m;
}

// A stiff contact with a strong viscous term (D05-like): stable at every slip rate.
ExtendedModel stiffStableContact() {
    ExtendedModel m = softUnstableContact();
    m.law.epsT_N_per_m = 3e5;
    m.law.eta_s_per_m = 0.8;
    m.law.Dc_m = 3e-5;
    m.law.vc_mps = 0.15;
    return m;
}

// 3 s of harmonic slip (2 mm, 4 Hz: |V| up to 0.05 m/s) recorded at 1 kHz; the force is the
// model's own at a fine step (120 law steps per sample) plus white noise of 0.01 N.
IdentifyRun recordedRun(const ExtendedModel& m) {
    const int fine = 120;
    const double w = 2 * M_PI * 4.0, A = 2e-3, tN = 6.2;
    std::vector<double> tf, gf;
    for (int i = 0; i <= 3000 * fine; ++i) {
        tf.push_back(i * 1e-3 / fine);
        gf.push_back(A * std::sin(w * tf.back()));
    }
    RunContext ctx;
    ctx.normalForce_N = tN;
    const ExtendedTrace tr = simulateExtendedPrescribed(m, ctx, tf, gf, nullptr, 1);
    IdentifyRun r;
    r.file = "run.csv";
    r.setup = SetupKind::Prescribed;
    r.normalForce_N = tN;
    std::mt19937_64 rng(7);
    std::normal_distribution<double> nd(0.0, 0.01);
    for (int i = 0; i <= 3000; ++i) {
        const size_t k = static_cast<size_t>(i * fine);
        r.t_s.push_back(tf[k]);
        r.slip_m.push_back(gf[k]);
        r.relVel_mps.push_back(A * w * std::cos(w * tf[k]));
        r.force_N.push_back(tr.contactForce_N[k] + nd(rng));
    }
    return r;
}

LawResolution check(const ExtendedModel& m, std::vector<IdentifyRun>& runs) {
    IdentifyOptions opt;
    opt.decimate = 2;  // law steps of 1 ms, as identify takes a 1 kHz rig recording
    Context cx;
    int dec = 0;
    std::string why;
    if (!prepareContext(runs, opt, cx, dec, why)) return {};
    return checkLawResolution(cx, m, kNaN, kLawResolutionRefinement);
}

}  // namespace

class TestLawResolution : public QObject {
    Q_OBJECT
private slots:
    void unstableSoftContactIsNotResolved() {
        const ExtendedModel m = softUnstableContact();
        std::vector<IdentifyRun> runs = {recordedRun(m)};
        const LawResolution r = check(m, runs);
        QVERIFY(r.checked);
        QCOMPARE(r.refinement, kLawResolutionRefinement);
        QCOMPARE(r.runs.size(), size_t(1));
        QVERIFY2(!r.resolved(), qPrintable(QString("change %1 N, noise %2 N").arg(r.runs[0].change_N).arg(r.runs[0].noise_N)));
        const std::string t = lawResolutionText(r);
        QVERIFY(t.find("run.csv") != std::string::npos);
        QVERIFY(t.find("--substeps") != std::string::npos);
    }

    void stiffStableContactIsResolved() {
        const ExtendedModel m = stiffStableContact();
        std::vector<IdentifyRun> runs = {recordedRun(m)};
        const LawResolution r = check(m, runs);
        QVERIFY(r.checked);
        QVERIFY2(r.resolved(), qPrintable(QString("change %1 N, noise %2 N").arg(r.runs[0].change_N).arg(r.runs[0].noise_N)));
        QVERIFY(lawResolutionText(r).empty());
        // The noise level is the residual's, read off the data: near the 0.01 N put in.
        QVERIFY2(r.runs[0].noise_N > 0.005 && r.runs[0].noise_N < 0.02, qPrintable(QString::number(r.runs[0].noise_N)));
    }

    // The refined law run is the law at the finer step along the same recorded input. At the
    // step the data were made with (1 ms / 120: refinement 120 of the 2 law steps per used
    // sample of 2 ms) it reproduces them to the noise put in (0.01 N); at every other step tried, coarser
    // or finer, it is off by far more: on this contact the prediction does not converge as the
    // step shrinks (measured: 0.34, 0.29, 0.41, 0.011, 0.20 N at refinements 1, 8, 60, 120, 240),
    // which is why the check compares two steps instead of trusting either.
    void refinedRunAtTheDataStepReproducesThem() {
        const ExtendedModel m = softUnstableContact();
        std::vector<IdentifyRun> runs = {recordedRun(m)};
        IdentifyOptions opt;
        opt.decimate = 2;
        Context cx;
        int dec = 0;
        std::string why;
        QVERIFY2(prepareContext(runs, opt, cx, dec, why), why.c_str());
        const Prepared& p = cx.runs[0];
        QCOMPARE(dec, 2);
        QCOMPARE(opt.substeps, 2);
        QVERIFY(!p.stepSlip.empty());
        std::vector<double> rms;
        for (int refinement : {1, 8, 60, 120, 240}) {
            LawRun law;
            QVERIFY(simulateLawRun(cx, p, m, law, refinement));
            double ss = 0;
            size_t n = 0;
            for (size_t i = p.size() / 3; i < p.size(); ++i, ++n) ss += std::pow(law.contactForce_N[i] - p.F[i], 2);
            rms.push_back(std::sqrt(ss / static_cast<double>(n)));
        }
        const QString msg = QString("RMS error at refinement 1, 8, 60, 120, 240: %1, %2, %3, %4, %5 N")
                                .arg(rms[0]).arg(rms[1]).arg(rms[2]).arg(rms[3]).arg(rms[4]);
        QVERIFY2(rms[3] < 0.013, qPrintable(msg));
        for (size_t k : {0, 1, 2, 4}) QVERIFY2(rms[k] > 0.1, qPrintable(msg));
    }

    // Without a run there is nothing to check: unchecked, and no text.
    void noRunsIsUnchecked() {
        Context cx;
        IdentifyOptions opt;
        cx.opt = &opt;
        const LawResolution r = checkLawResolution(cx, softUnstableContact(), kNaN, 8);
        QVERIFY(!r.checked);
        QVERIFY(lawResolutionText(r).empty());
    }
};

QTEST_GUILESS_MAIN(TestLawResolution)
#include "tst_law_resolution.moc"
