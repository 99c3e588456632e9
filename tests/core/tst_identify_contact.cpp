// The identify loop, blind, on data with one contact or output effect switched on.
#include <QtTest/QtTest>

#include "identify_synth.hpp"

using namespace stickslip::identify;

namespace {

// knownMiss: a documented miss of the current loop (docs/identify-results.md); the test then
// expects the failure and turns into XPASS (a failure) the day the loop finds the effect.
void expectFound(const ExtendedModel& truth, unsigned seed, const std::string& name, const char* knownMiss = nullptr) {
    auto runs = synth::makeRuns(truth, 2.0, 0.02, seed);
    const IdentifyResult r = identifyEffects(runs, synth::testOptions());
    QVERIFY2(r.ok, r.message.c_str());
    // Whatever it adds, it never adds an effect other than the one in the data first.
    if (!r.effectsAdded.empty() && knownMiss) QCOMPARE(r.effectsAdded.front().name, name);
    if (knownMiss) QEXPECT_FAIL("", knownMiss, Abort);
    QVERIFY2(!r.effectsAdded.empty(), ("nothing added; expected " + name).c_str());
    QCOMPARE(r.effectsAdded.front().name, name);
    QVERIFY(r.after.validationNrmse < 0.8 * r.before.validationNrmse);
    QVERIFY(!r.effectsAdded.front().pointedBy.empty());
}

}  // namespace

class TestIdentifyContact : public QObject {
    Q_OBJECT
private slots:
    void findsStickHealing() {
        auto m = synth::trueModel();
        m.effects.stickHealing = StickHealing{0.08, 0.05, 2e-4};
        expectFound(m, 11, "stick_healing");
    }
    void findsBacklash() {
        auto m = synth::trueModel();
        m.effects.backlash = Backlash{2e-4};
        expectFound(m, 12, "backlash",
                    "known miss: a 0.2 mm dead band in this short prescribed data is not added (dBIC not below the margin)");
    }
    void findsPreslidingCompliance() {
        auto m = synth::trueModel();
        m.effects.preslidingCompliance = PreslidingCompliance{2e4};
        expectFound(m, 13, "presliding_compliance");
    }
    void findsViscousDamping() {
        auto m = synth::trueModel();
        m.effects.viscousDamping = ViscousDamping{0.5};
        expectFound(m, 14, "viscous_damping",
                    "known miss: in the prescribed set-up a parallel dashpot c_p V is nearly the law's own eta t_N V "
                    "while sliding; the baseline absorbs it into eta");
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
