// The identify loop, blind, on data made by the project's own simulator with one effect of
// the friction law switched on (or none): it names the right effect first, adds nothing for
// 'none', and cuts the held-out error.
#include <QtTest/QtTest>

#include <algorithm>

#include <cmath>

#include "identify_checks.hpp"
#include "identify_synth.hpp"

using namespace stickslip::identify;

namespace {

IdentifyResult runLoop(const ExtendedModel& truth, unsigned seed) {
    auto runs = synth::makeRuns(truth, 2.0, 0.02, seed);
    return identifyEffects(runs, synth::testOptions());
}

// The loop on runs made with `truth`, its effect not among the candidates (backlash and the
// sensor mass only).
IdentifyResult withoutItsCandidate(const ExtendedModel& truth, const char* what) {
    auto o = synth::testOptions();
    o.candidates = {"backlash", "sensor_inertia"};
    const IdentifyResult r = identifyEffects(synth::makeRuns(truth, 2.0, 0.02, 2), o);
    qInfo("%s without candidate: added %zu; %s", what, r.effectsAdded.size(), r.structureNote.c_str());
    return r;
}

void expectFound(const IdentifyResult& r, const std::string& name) {
    QVERIFY2(r.ok, r.message.c_str());
    QVERIFY2(!r.effectsAdded.empty(), ("nothing added; expected " + name).c_str());
    QCOMPARE(r.effectsAdded.front().name, name);
    QVERIFY(r.after.validationNrmse < 0.8 * r.before.validationNrmse);
    QVERIFY(r.after.fitNrmse < r.before.fitNrmse);
    // The report names it with catalogue names and parameters.
    const auto j = toJson(r);
    QCOMPARE(j["effects_added"][0]["name"].get<std::string>(), name);
    QVERIFY(j["candidates"].size() >= 8);
    // The selection's held-out and size tests were made and passed (4 runs: 3 degrees of freedom).
    synth::verifyAcceptedPassedSelection(r, 4, 3.182446);
    synth::verifyTimeline(r);
    qInfo("%s: Ljung-Box p %.3g, structure ratio %.3f", name.c_str(), r.diagnosticsAfter.whiteness.pValue,
          r.diagnosticsAfter.whiteness.structureRatio);
}

}  // namespace

class TestIdentifyLaw : public QObject {
    Q_OBJECT
private slots:
    // Two effects that trade off: runs recorded in order of rising load, so the slip
    // accumulated before each run grows with its load, and a load dependence of μ and a wear
    // drift both explain the force's rise over the runs (size correlation −0.98 in the joint
    // fit). The loop adds one and reports the other as confounded with it, not both.
    void confoundedEffectsAreNotBothAdded() {
        auto m = synth::trueModel();
        m.effects.normalLoadMu = NormalLoadMu{0.01};
        m.effects.wearDrift = WearDrift{0.5};
        std::vector<synth::RunConfig> cfgs;
        for (double tN : {5.0, 7.0, 9.0, 11.0, 13.0}) cfgs.push_back({2e-3, 2.0, tN});
        auto o = synth::testOptions();
        o.maxEffects = 3;
        o.candidates = {"normal_load_mu", "wear_drift", "direction_asymmetry"};
        // Every run has the same speed profile: with v_c free the baseline ends in the μ–C1–v_c
        // valley, where the joint fit is not identifiable and its correlation matrix undefined.
        // The trade-off of the two sizes is still seen (pairCorrelation holds the valley).
        const IdentifyResult r = identifyEffects(synth::makeRunsFrom(m, cfgs, 2.0, 0.02, 3), o);
        QVERIFY2(r.ok, r.message.c_str());
        QCOMPARE(r.effectsAdded.size(), size_t(1));
        const AddedEffect& added = r.effectsAdded.front();
        const std::string other = added.name == "normal_load_mu" ? "wear_drift" : "normal_load_mu";
        QVERIFY2(added.name == "normal_load_mu" || added.name == "wear_drift", added.name.c_str());
        QCOMPARE(added.confoundedWith, std::vector<std::string>{other});
        bool reported = false;
        for (const CandidateScore& c : r.candidates)
            if (c.name == other) {
                reported = true;
                QCOMPARE(c.confoundedWith, added.name);
                QVERIFY(std::abs(c.sizeCorrelation.at(added.name)) > 0.949);
                QVERIFY2(c.reason.find("confounded with " + added.name) == 0, c.reason.c_str());
                QVERIFY(!c.accepted);
                qInfo("%s confounded with %s: size correlation %.3f (dBIC %.1f)", other.c_str(), added.name.c_str(),
                      c.sizeCorrelation.at(added.name), c.deltaBic);
            }
        QVERIFY(reported);
        const auto j = toJson(r);
        QCOMPARE(j["effects_added"][0]["confounded_with"][0].get<std::string>(), other);
    }
    // A start where the law predicts no force at all (C1 = 0.5 > μ's share at v_c = 0.003: the
    // strength is negative and the return map holds F = 0) has a zero Jacobian: the solver
    // stopped there after one iteration at fit NRMSE 1.00007 and the loop went on from it. It is
    // now a solver failure, retried from the default law, and said so; the baseline is then the
    // good start's.
    void baselineThatExplainsNothingIsRetried() {
        auto o = synth::testOptions();
        o.maxEffects = 0;
        o.multistarts = 2;
        const auto runs = synth::makeRuns(synth::trueModel(), 2.0, 0.02, 1);
        const IdentifyResult good = identifyEffects(runs, o);
        QVERIFY2(good.ok, good.message.c_str());
        // The report shows the first baseline fit's starts: each one's cost, the one kept (the
        // lowest) and a summary line per start with its evaluations.
        const auto solver = toJson(good)["baseline"]["first_fit_solver"];
        QCOMPARE(solver["start_costs"].size(), size_t(2));
        const int best = solver["best_start"].get<int>();
        QVERIFY(best == 0 || best == 1);
        for (const auto& c : solver["start_costs"])
            QVERIFY(c.is_null() || c.get<double>() >= solver["start_costs"][best].get<double>());
        const std::string summary = solver["summary"].get<std::string>();
        QVERIFY2(summary.find("start 0: cost") != std::string::npos && summary.find("start 1: ") != std::string::npos &&
                     summary.find(" evaluations\n") != std::string::npos,
                 summary.c_str());
        o.start.C1 = 0.5;
        o.start.vc_mps = 0.003;
        o.start.eta_s_per_m = 1.0;
        const IdentifyResult r = identifyEffects(runs, o);
        QVERIFY2(r.ok, r.message.c_str());
        qInfo("%s", r.baselineNote.c_str());
        QVERIFY2(r.baselineNote.find("explained none of the force") != std::string::npos, r.baselineNote.c_str());
        QVERIFY2(r.baselineNote.find("refitted from the default law") != std::string::npos, r.baselineNote.c_str());
        QVERIFY(std::abs(r.before.fitNrmse - good.before.fitNrmse) <= 1e-3 * good.before.fitNrmse);
    }
    // Data without the state term (C1 = 0: K1 ≡ 0) push the baseline to a bound where the term
    // vanishes: C1 to its lower bound or v_c to its upper one (α = −V/v_c → 0; measured: v_c,
    // 10 m/s). That bound is checked from a second start in the middle of the range, which ends
    // on it again: reported as the data's answer, not a solver failure, and the baseline kept.
    void aParameterOnItsBoundIsCheckedFromASecondStart() {
        auto truth = synth::trueModel();
        truth.law.C1 = 0.0;
        auto o = synth::testOptions();
        o.maxEffects = 0;
        const IdentifyResult r = identifyEffects(synth::makeRuns(truth, 2.0, 0.02, 1), o);
        QVERIFY2(r.ok, r.message.c_str());
        qInfo("%s", r.baselineNote.c_str());
        const BoundVerdict* hit = nullptr;
        for (const BoundVerdict& b : r.baselineBounds)
            if ((b.name == "C1" && b.side == "lower") || (b.name == "vc" && b.side == "upper")) hit = &b;
        QVERIFY2(hit, r.baselineNote.c_str());
        QVERIFY(!hit->solverFailure && !hit->refitted);
        QVERIFY(std::abs(std::log(hit->retryStart / hit->bound)) > std::log(100.0));  // started far from it
        QVERIFY(std::abs(hit->retryValue / hit->bound - 1.0) < 0.01);  // and ended on it again
        QVERIFY2(r.baselineNote.find(hit->name + " ended on its " + hit->side + " bound") != std::string::npos,
                 r.baselineNote.c_str());
        QVERIFY(r.baselineNote.find("on the bound again: the bound is the data's answer") != std::string::npos);
        const auto j = toJson(r);
        bool reported = false;
        for (const auto& b : j["baseline"]["at_bound"])
            if (b["parameter"] == hit->name) reported = b["verdict"] == "the data's answer";
        QVERIFY(reported);
    }
    void noneAddsNothing() {
        const IdentifyResult r = runLoop(synth::trueModel(), 1);
        QVERIFY2(r.ok, r.message.c_str());
        QVERIFY2(r.effectsAdded.empty(), r.effectsAdded.empty() ? "" : r.effectsAdded.front().name.c_str());
        QCOMPARE(r.after.validationNrmse, r.before.validationNrmse);
        for (const auto& c : r.candidates) QVERIFY(!c.accepted && !c.reason.empty());
        synth::verifyTimeline(r);
        if (QTest::currentTestFailed()) return;
        // A candidate stopped by the ΔBIC margin is told how much evidence the runs could give
        // (n_eff and what limits it), not that noise explains it: the margin test cannot tell
        // noise from a real but weakly supported gain (the damper's six 0.5 Hz runs: backlash
        // at ΔBIC −4 with n_eff = 54 slip episodes, session 37).
        int byMargin = 0;
        for (const auto& c : r.candidates) {
            if (!c.applicable) continue;
            QVERIFY2(std::isfinite(c.neff) && c.neff >= 2.0, c.name.c_str());
            QVERIFY2(c.neffLimit == "slip episodes" || c.neffLimit == "independent residuals (n/tau_int)" ||
                         c.neffLimit == "segments",
                     c.neffLimit.c_str());
            if (c.reason.find("is not below -") == std::string::npos) continue;
            ++byMargin;
            QVERIFY2(c.reason.find("n_eff = ") != std::string::npos && c.reason.find(c.neffLimit) != std::string::npos,
                     c.reason.c_str());
            QVERIFY2(c.reason.find("noise explains") == std::string::npos, c.reason.c_str());
        }
        QVERIFY(byMargin > 0);
        const auto j = toJson(r);
        for (const auto& c : j["candidates"])
            if (c["applicable"].get<bool>()) QVERIFY(c["score"]["n_eff"].is_number() && c["score"]["n_eff_limit"].is_string());
        QVERIFY(j["effects_added"].empty());
        QVERIFY(j.contains("unexplained"));
        QVERIFY(j["before"].contains("fit_nrmse") && j["before"].contains("validation_nrmse"));
        qInfo("none: Ljung-Box p %.3g, structure ratio %.3f", r.diagnosticsAfter.whiteness.pValue,
              r.diagnosticsAfter.whiteness.structureRatio);
    }
    // Data the model family reproduces exactly (same law steps as the data were made with:
    // every sample, 4 steps per sample) plus white force noise: the residual is consistent
    // with noise and nothing is unexplained. (With the faster default resolution of these
    // tests, 2 ms samples and 1 ms steps against 0.25 ms in the data, the law's
    // discretisation differs visibly, and the flag rightly reports that structure.)
    void modelThatFitsLeavesNothingUnexplained() {
        auto o = synth::testOptions();
        o.decimate = 1;
        o.substeps = 4;
        o.maxEffects = 0;
        const IdentifyResult r = identifyEffects(synth::makeRuns(synth::trueModel(), 2.0, 0.02, 1), o);
        QVERIFY2(r.ok, r.message.c_str());
        qInfo("matched resolution: Ljung-Box p %.3g, structure ratio %.3f, fit NRMSE %.4f", r.diagnosticsAfter.whiteness.pValue,
              r.diagnosticsAfter.whiteness.structureRatio, r.after.fitNrmse);
        QVERIFY2(!r.unexplained, r.unexplainedReason.c_str());
        QVERIFY(!toJson(r)["unexplained"].get<bool>());
        // The law channel is resolved at this step: 8x finer steps change the prediction by less
        // than the residual's noise level, run by run, and the report says so.
        QVERIFY(r.lawResolution.checked);
        QVERIFY(!r.lawResolution.runs.empty());
        for (const LawResolution::Run& x : r.lawResolution.runs)
            QVERIFY2(x.resolved() && x.noise_N > 0.0, qPrintable(QString("%1: change %2 N, noise %3 N")
                                                                     .arg(x.file.c_str()).arg(x.change_N).arg(x.noise_N)));
        QVERIFY(toJson(r)["law_resolution"]["resolved"].get<bool>());
        QVERIFY(lawResolutionText(r.lawResolution).empty());
    }
    // The effect is in the data but not among the candidates: the loop must not claim one of
    // the others for it, and must report the structure that remains. A direction offset of μ
    // (0.05) repeats from run to run and is reported (nothing else is added); the old verdict
    // (Ljung–Box and a fixed structure ratio) passed it as white (p 0.84, ratio 0.11).
    void structureWithoutCandidateIsUnexplained() {
        auto m = synth::trueModel();
        m.effects.directionAsymmetry = DirectionAsymmetry{0.05};
        const IdentifyResult r = withoutItsCandidate(m, "asymmetry");
        QVERIFY2(r.ok, r.message.c_str());
        QVERIFY(r.effectsAdded.empty());
        QVERIFY2(r.unexplained, r.structureNote.c_str());
        // Every signal's line per sign carries the direction offset, so signV is among the
        // strongest, not necessarily first.
        const auto& by = r.diagnosticsAfter.structure.bySignal;
        QVERIFY(by.size() >= 3);
        QVERIFY2(std::any_of(by.begin(), by.begin() + 3, [](const SignalGain& g) { return g.signal == "signV"; }),
                 r.unexplainedReason.c_str());
        QVERIFY2(r.unexplainedReason.find("strongest signals alone") != std::string::npos, r.unexplainedReason.c_str());
        QVERIFY(toJson(r)["unexplained"].get<bool>());
    }
    // A known gap (docs/identify-results.md, session 73): a 10 ms frictional lag without its
    // candidate, on these four 2 s runs at different frequencies and amplitudes, is taken up in
    // part by a sensor mass, and what is left does not repeat from run to run (held-out log MSE
    // ratios −0.19, 0.12, −0.005, 0), so it is not reported. QEXPECT_FAIL: this test fails
    // loudly (XPASS) once the verdict sees it.
    void lagWithoutCandidateIsAKnownGap() {
        auto m = synth::trueModel();
        m.effects.frictionalLag = FrictionalLag{0.01};
        const IdentifyResult r = withoutItsCandidate(m, "lag");
        QVERIFY2(r.ok, r.message.c_str());
        QEXPECT_FAIL("", "lag structure left after a stand-in does not repeat from run to run at this data size", Continue);
        QVERIFY(r.effectsAdded.empty() && r.unexplained);
    }
    void findsFrictionalLag() {
        auto m = synth::trueModel();
        m.effects.frictionalLag = FrictionalLag{0.01};
        const IdentifyResult r = runLoop(m, 2);
        expectFound(r, "frictional_lag");
        QVERIFY(std::abs(r.effectsAdded.front().params[0].value - 0.01) < 0.003);
    }
    void findsNormalLoadMu() {
        auto m = synth::trueModel();
        m.effects.normalLoadMu = NormalLoadMu{-0.015};
        const IdentifyResult r = runLoop(m, 3);
        expectFound(r, "normal_load_mu");
        QVERIFY(std::abs(r.effectsAdded.front().params[0].value + 0.015) < 0.003);
    }
    void findsDirectionAsymmetry() {
        auto m = synth::trueModel();
        m.effects.directionAsymmetry = DirectionAsymmetry{0.05};
        const IdentifyResult r = runLoop(m, 4);
        expectFound(r, "direction_asymmetry");
        QVERIFY(std::abs(r.effectsAdded.front().params[0].value - 0.05) < 0.01);
    }
    void findsWearDrift() {
        auto m = synth::trueModel();
        m.effects.wearDrift = WearDrift{0.4};
        const IdentifyResult r = runLoop(m, 5);
        expectFound(r, "wear_drift");
        QVERIFY(std::abs(r.effectsAdded.front().params[0].value - 0.4) < 0.1);
    }
};

QTEST_GUILESS_MAIN(TestIdentifyLaw)
#include "tst_identify_law.moc"
