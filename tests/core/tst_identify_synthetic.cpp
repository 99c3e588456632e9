// The identify loop with its default options on the independent simulator's rig runs
// (../shared/data/synthetic), checked against the answer keys (read only to check, never
// given to the loop): D05 has no hidden effect, so nothing may be added; D03 hides a
// frictional lag, which must be named and must cut the held-out error; D01, D02 and D04 must
// get their hidden effect and nothing else.
#include <QtTest/QtTest>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/identify/identify.hpp"
#include "core/identify/preprocess.hpp"
#include "core/io/dataset.hpp"

using namespace stickslip;
using namespace stickslip::identify;

namespace {

const std::string kShared = STICKSLIP_SHARED_DIR;

nlohmann::json answer(const std::string& set) {
    std::ifstream in(kShared + "/data/synthetic/answers/" + set + ".json");
    return nlohmann::json::parse(in);
}

std::string answerEffect(const std::string& set) { return answer(set).at("effect").get<std::string>(); }

IdentifyResult identifySet(const std::string& set) {
    const std::string dir = kShared + "/data/synthetic/" + set;
    std::vector<std::string> files;
    for (int i = 1; i <= 5; ++i) files.push_back(dir + "/run_0" + std::to_string(i) + ".csv");
    io::DatasetOptions dopt;
    dopt.manifestPath = dir + "/manifest.json";
    io::Dataset ds;
    io::DatasetError err;
    if (!io::loadDataset(files, dopt, ds, err)) qFatal("%s", err.what().c_str());
    std::vector<IdentifyRun> runs;
    for (const io::Run& r : ds.runs) {
        CleanRun c;
        IdentifyRun ir;
        std::string why;
        if (!preprocessRun(r, PreprocessSettings{}, c, &why) || !makeIdentifyRun(c, SetupKind::Dynamics, ir, &why))
            qFatal("%s", why.c_str());
        runs.push_back(std::move(ir));
    }
    return identifyEffects(std::move(runs), IdentifyOptions{});
}

QString added(const IdentifyResult& r) {
    QStringList names;
    for (const AddedEffect& e : r.effectsAdded) names << QString::fromStdString(e.name);
    return names.join(", ");
}

}  // namespace

class TstIdentifySynthetic : public QObject {
    Q_OBJECT
private slots:
    void noEffectDatasetGetsNothing() {
        QCOMPARE(answerEffect("D05"), std::string("none"));
        const IdentifyResult r = identifySet("D05");
        QVERIFY2(r.ok, r.message.c_str());
        QVERIFY2(r.effectsAdded.empty(), qPrintable("added: " + added(r)));
        QVERIFY(!r.candidates.empty());  // every candidate was tried and rejected
        for (const CandidateScore& c : r.candidates) QVERIFY2(!c.accepted, c.name.c_str());
    }

    // Issue 6 (selection): on D01 and D04 the loop used to add the key's effect and THEN a
    // frictional lag (and on D04 a sensor inertia) that the data do not have, because a small
    // lag absorbs a systematic error of the equation-error residual and passes the ΔBIC margin.
    // With the held-out paired test and the jackknife size test it must stop after the key's
    // effect, and the key's value must lie in the 95 % interval of the jackknife error. D02
    // (normal_load_mu) never had the problem and is held to the same standard.
    void onlyTheHiddenEffectIsAdded_data() {
        QTest::addColumn<QString>("set");
        QTest::newRow("D01") << "D01";
        QTest::newRow("D02") << "D02";
        QTest::newRow("D04") << "D04";
    }
    void onlyTheHiddenEffectIsAdded() {
        QFETCH(QString, set);
        const nlohmann::json key = answer(set.toStdString());
        const IdentifyResult r = identifySet(set.toStdString());
        QVERIFY2(r.ok, r.message.c_str());
        QVERIFY2(r.effectsAdded.size() == 1 && r.effectsAdded.front().name == key.at("effect").get<std::string>(),
                 qPrintable("added: " + added(r)));
        const AddedEffect& e = r.effectsAdded.front();
        const double truth = key.at("effect_params").at(e.params.front().name).get<double>();
        bool checked = false;
        for (const CandidateScore& c : r.candidates) {
            qInfo("%s round %d dBIC %.2f held-out p %.3g size %.4g +- %.3g (crit %.2f): %s", c.name.c_str(), c.round, c.deltaBic,
                  c.heldOutP, c.sizeValue, c.sizeStderr, c.sizeCritical, c.accepted ? "added" : c.reason.c_str());
            if (!c.accepted) continue;
            QVERIFY2(std::abs(c.sizeValue - truth) <= c.sizeCritical * c.sizeStderr,
                     qPrintable(QString("%1 = %2, key %3, jackknife s.e. %4").arg(QString::fromStdString(c.name))
                                    .arg(c.sizeValue).arg(truth).arg(c.sizeStderr)));
            checked = true;
        }
        QVERIFY(checked);
        QVERIFY(r.after.validationNrmse < r.before.validationNrmse);
    }

    void hiddenFrictionalLagIsNamed() {
        QCOMPARE(answerEffect("D03"), std::string("frictional_lag"));
        const IdentifyResult r = identifySet("D03");
        QVERIFY2(r.ok, r.message.c_str());
        QVERIFY2(!r.effectsAdded.empty() && r.effectsAdded.front().name == "frictional_lag",
                 qPrintable("added: " + added(r)));
        QVERIFY(r.after.validationNrmse < r.before.validationNrmse);
    }
};

QTEST_APPLESS_MAIN(TstIdentifySynthetic)
#include "tst_identify_synthetic.moc"
