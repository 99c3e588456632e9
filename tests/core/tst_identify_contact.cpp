// The identify loop, blind, on data with one contact or output effect switched on.
#include <QtTest/QtTest>

#include "identify_checks.hpp"
#include "identify_synth.hpp"

using namespace stickslip::identify;

namespace {

// knownMiss: a documented miss of the current loop (docs/identify-results.md); the test then
// expects the failure and turns into XPASS (a failure) the day the loop finds the effect.
void expectFound(const ExtendedModel& truth, unsigned seed, const std::string& name, const char* knownMiss = nullptr) {
    auto runs = synth::makeRuns(truth, 2.0, 0.02, seed);
    const IdentifyResult r = identifyEffects(runs, synth::testOptions());
    QVERIFY2(r.ok, r.message.c_str());
    for (const auto& c : r.candidates)
        qInfo("%s: dBIC %.2f fit NRMSE %.4f %s", c.name.c_str(), c.deltaBic, c.fitNrmse, c.reason.c_str());
    qInfo("before fit %.4f held-out %.4f", r.before.fitNrmse, r.before.validationNrmse);
    // Whatever it adds, it never adds an effect other than the one in the data first.
    if (!r.effectsAdded.empty() && knownMiss) QCOMPARE(r.effectsAdded.front().name, name);
    if (knownMiss) QEXPECT_FAIL("", knownMiss, Abort);
    QVERIFY2(!r.effectsAdded.empty(), ("nothing added; expected " + name).c_str());
    QCOMPARE(r.effectsAdded.front().name, name);
    QVERIFY(r.after.validationNrmse < 0.8 * r.before.validationNrmse);
    QVERIFY(!r.effectsAdded.front().pointedBy.empty());
    // The selection's held-out and size tests were made and passed (4 runs: 3 degrees of freedom).
    synth::verifyAcceptedPassedSelection(r, 4, 3.182446);
}

}  // namespace

class TestIdentifyContact : public QObject {
    Q_OBJECT
private slots:
    void findsStickHealing() {
        auto m = synth::trueModel();
        m.effects.stickHealing = StickHealing{0.02, 0.005, 2e-4};
        expectFound(m, 11, "stick_healing");
    }
    void findsBacklash() {
        auto m = synth::trueModel();
        m.effects.backlash = Backlash{2e-4};
        expectFound(m, 12, "backlash");
    }
    void findsPreslidingCompliance() {
        auto m = synth::trueModel();
        m.effects.preslidingCompliance = PreslidingCompliance{2e4};
        expectFound(m, 13, "presliding_compliance");
    }
    // A dashpot c_p = ζ t_N (1 s/m) in parallel with the contact, in the prescribed set-up,
    // adds c_p V = ζ t_N V to the force. While sliding V is the slip rate, so this is exactly
    // the law's own η t_N λ̇ with η → η + ζ; in stick V is the tiny elastic rate Ḟ/ε_T. The
    // data cannot tell the two apart: the effect is not identifiable here (it is in the
    // dynamics set-up, where ζ damps the rig). What the loop must do: explain the data with
    // the baseline (η̂ ≈ η + ζ), and add no other effect for it.
    void viscousDampingIsAbsorbedByEtaPrescribed() {
        auto m = synth::trueModel();
        m.effects.viscousDamping = ViscousDamping{0.5};
        auto runs = synth::makeRuns(m, 2.0, 0.02, 14);
        // Undecimated (written in session 18, when the law was driven by a line between decimated
        // samples that cut the dwells' corners; the recorded slip drives it since session 20).
        auto o = synth::testOptions();
        o.decimate = 1;
        o.substeps = 1;
        const IdentifyResult r = identifyEffects(runs, o);
        QVERIFY2(r.ok, r.message.c_str());
        for (const auto& c : r.candidates)
            qInfo("%s: dBIC %.2f fit NRMSE %.4f, %s = %g", c.name.c_str(), c.deltaBic, c.fitNrmse,
                  c.params.empty() ? "" : c.params.front().name.c_str(), c.params.empty() ? 0.0 : c.params.front().value);
        if (!r.effectsAdded.empty()) QCOMPARE(r.effectsAdded.front().name, std::string("viscous_damping"));
        double eta = -1;
        for (const auto& p : r.baseline)
            if (p.name == "eta") eta = p.value;
        qInfo("baseline eta %.4f (law 0.8 + zeta 0.5), fit NRMSE %.4f", eta, r.before.fitNrmse);
        // The report says why: the candidate's size trades off with η (selection test 0's
        // variance inflation, read against the baseline's parameters).
        bool seen = false;
        for (const auto& c : r.candidates)
            if (c.name == "viscous_damping" && !c.accepted) {
                seen = true;
                qInfo("viscous_damping trades off with %s (correlation %.4f)", c.tradesOffWithBaseline.c_str(),
                      c.sizeCorrelation.count("eta") ? c.sizeCorrelation.at("eta") : 0.0);
                QCOMPARE(c.tradesOffWithBaseline, std::string("eta"));
                QVERIFY2(verdictOf(c).find("trades off with the baseline's eta (correlation -0.9") != std::string::npos,
                         verdictOf(c).c_str());
                QCOMPARE(toJson(r)["candidates"][static_cast<size_t>(&c - r.candidates.data())]["trades_off_with_baseline"].get<std::string>(),
                         std::string("eta"));
            }
        QVERIFY(seen || !r.effectsAdded.empty());
        QVERIFY(std::abs(eta - (0.8 + 0.5)) < 0.15);
        QVERIFY(r.before.fitNrmse < 0.03);
    }
    void findsSensorInertia() {
        auto m = synth::trueModel();
        m.effects.sensorInertia = SensorInertia{2.0};
        expectFound(m, 15, "sensor_inertia");
    }
    void badInputIsAStatusNotACrash() {
        std::vector<IdentifyRun> none;
        QVERIFY(!identifyEffects(none, synth::testOptions()).ok);
        auto runs = synth::makeRuns(synth::trueModel(), 0.5, 0.02, 1);
        runs[0].force_N.pop_back();
        const IdentifyResult r = identifyEffects(runs, synth::testOptions());
        QVERIFY(!r.ok);
        QVERIFY(r.message.find("synthetic_run_1") != std::string::npos);
        auto o = synth::testOptions();
        o.candidates = {"flux_capacitor"};
        QVERIFY(identifyEffects(synth::makeRuns(synth::trueModel(), 0.5, 0.02, 1), o).message.find("unknown effect") != std::string::npos);
    }
};

QTEST_GUILESS_MAIN(TestIdentifyContact)
#include "tst_identify_contact.moc"
