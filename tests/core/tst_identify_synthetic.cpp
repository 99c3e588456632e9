// The identify loop with its default options on the independent simulator's rig runs
// (../shared/data/synthetic), checked against the answer keys (read only to check, never
// given to the loop): D05 has no hidden effect, so nothing may be added; D03 hides a
// frictional lag, which must be named and must cut the held-out error.
#include <QtTest/QtTest>

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/identify/identify.hpp"
#include "core/identify/preprocess.hpp"
#include "core/io/dataset.hpp"

using namespace stickslip;
using namespace stickslip::identify;

namespace {

const std::string kShared = STICKSLIP_SHARED_DIR;

std::string answerEffect(const std::string& set) {
    std::ifstream in(kShared + "/data/synthetic/answers/" + set + ".json");
    return nlohmann::json::parse(in).at("effect").get<std::string>();
}

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
