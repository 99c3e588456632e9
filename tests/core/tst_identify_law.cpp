// The identify loop, blind, on data made by the project's own simulator with one effect of
// the friction law switched on (or none): it names the right effect first, adds nothing for
// 'none', and cuts the held-out error.
#include <QtTest/QtTest>

#include "identify_synth.hpp"

using namespace stickslip::identify;

namespace {

IdentifyResult runLoop(const ExtendedModel& truth, unsigned seed) {
    auto runs = synth::makeRuns(truth, 2.0, 0.02, seed);
    return identifyEffects(runs, synth::testOptions());
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
}

}  // namespace

class TestIdentifyLaw : public QObject {
    Q_OBJECT
private slots:
    void noneAddsNothing() {
        const IdentifyResult r = runLoop(synth::trueModel(), 1);
        QVERIFY2(r.ok, r.message.c_str());
        QVERIFY2(r.effectsAdded.empty(), r.effectsAdded.empty() ? "" : r.effectsAdded.front().name.c_str());
        QCOMPARE(r.after.validationNrmse, r.before.validationNrmse);
        for (const auto& c : r.candidates) QVERIFY(!c.accepted && !c.reason.empty());
        const auto j = toJson(r);
        QVERIFY(j["effects_added"].empty());
        QVERIFY(j.contains("unexplained"));
        QVERIFY(j["before"].contains("fit_nrmse") && j["before"].contains("validation_nrmse"));
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
