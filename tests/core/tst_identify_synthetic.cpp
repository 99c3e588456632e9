// The identify loop with its default options on all 18 of the independent simulator's rig
// sets (../shared/data/synthetic), checked against the answer keys (read only to check, never
// given to the loop): the set of effects added must be exactly the key's set (none, one or
// two), no extra and none missing. Each set is its own CTest entry (tests/CMakeLists.txt runs
// one data row per entry). Sets the current loop gets wrong are listed in kKnownMiss with what
// goes wrong (docs/identify-results.md); they are expected failures, and turn into an XPASS
// (a failure) the day the loop gets them right, so the list cannot go stale.
#include <QtTest/QtTest>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <nlohmann/json.hpp>

#include "core/identify/effects/registry.hpp"
#include "core/identify/identify.hpp"
#include "core/identify/preprocess.hpp"
#include "core/io/dataset.hpp"
#include "rig_set_loader.hpp"

using namespace stickslip;
using namespace stickslip::identify;

namespace {

const std::string kShared = STICKSLIP_SHARED_DIR;

nlohmann::json answer(const std::string& set) {
    std::ifstream in(kShared + "/data/synthetic/answers/" + set + ".json");
    return nlohmann::json::parse(in);
}

// The key's effects: "effects" (a list) where present, else "effect" ("none" = no effect).
std::set<std::string> answerEffects(const std::string& set) {
    const nlohmann::json key = answer(set);
    std::set<std::string> out;
    if (key.contains("effects") && key["effects"].is_array()) {
        for (const auto& e : key["effects"]) out.insert(e.get<std::string>());
    } else if (key.at("effect").get<std::string>() != "none") {
        out.insert(key.at("effect").get<std::string>());
    }
    return out;
}

// Measured with the code of this commit (docs/identify-results.md, "all 18 sets").
const std::map<std::string, const char*> kKnownMiss = {
    // Empty since session 46: D18's stick healing, missed through session 45, is found since the
    // baseline's D_c and ε_T scans got a second pass (b 0.0128, t_c 0.78 ms, D_h 15.4 um against the
    // key's 0.0115, 1.6 ms, 16.6 um). A set the loop gets wrong goes here, with what goes wrong.
};

// The first `nRuns` runs of a set, each cut to its first `maxSeconds` (all of it by default).
std::vector<IdentifyRun> loadRuns(const std::string& set, int nRuns, double maxSeconds) {
    return rigset::loadRuns(kShared + "/data/synthetic/" + set, nRuns, maxSeconds);
}

// The loop on the first `nRuns` runs of a set, each cut to its first `maxSeconds`.
IdentifyResult identifySet(const std::string& set, const IdentifyOptions& opt = IdentifyOptions{}, int nRuns = 5,
                           double maxSeconds = INFINITY) {
    return identifyEffects(loadRuns(set, nRuns, maxSeconds), opt);
}

// The error floor of the loop's residual on a set without an effect: its errors with the answer
// key's law, mass and damping (only ζ refitted, from the key's value), no effect. What any fit can
// reach on these runs, whatever the noise does to the residual (on compliant contacts the
// measured slip's noise enters the law channel through ε_T, so the floor is not the force noise).
ModelErrors truthErrors(const std::string& set, std::vector<IdentifyRun> runs) {
    const nlohmann::json bp = answer(set).at("baseline_params");
    for (IdentifyRun& r : runs) r.nominalMass_kg = bp.at("m").get<double>();
    IdentifyOptions o;
    o.start.mu = bp.at("mu");
    o.start.C1 = bp.at("C1");
    o.start.eta_s_per_m = bp.at("eta");
    o.start.Dc_m = bp.at("Dc");
    o.start.vc_mps = bp.at("vc");
    o.start.epsT_N_per_m = bp.at("epsT");
    o.start.r = bp.at("r");
    o.freeLaw.clear();
    o.fitMass = false;
    o.zetaNominal = bp.at("zeta");
    o.maxEffects = 0;
    o.nullReplicas = 0;
    o.heldOutRestart = false;
    const IdentifyResult r = identifyEffects(std::move(runs), o);
    if (!r.ok) qFatal("%s: the key's model: %s", set.c_str(), r.message.c_str());
    return r.before;
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
    void exactEffectSet_data() {
        QTest::addColumn<QString>("set");
        for (int i = 1; i <= 18; ++i) {
            const QString set = QString("D%1").arg(i, 2, 10, QChar('0'));
            QTest::newRow(qPrintable(set)) << set;
        }
    }
    void exactEffectSet() {
        QFETCH(QString, set);
        const std::string name = set.toStdString();
        const std::set<std::string> truth = answerEffects(name);
        const std::vector<IdentifyRun> runs = loadRuns(name, 5, INFINITY);
        const IdentifyResult r = identifyEffects(runs, IdentifyOptions{});
        QVERIFY2(r.ok, r.message.c_str());
        for (const CandidateScore& c : r.candidates)
            qInfo("%s round %d dBIC %.2f held-out p %.3g size %.4g +- %.3g (crit %.2f): %s", c.name.c_str(), c.round, c.deltaBic,
                  c.heldOutP, c.sizeValue, c.sizeStderr, c.sizeCritical, c.accepted ? "added" : c.reason.c_str());
        qInfo("%s: held-out NRMSE before %.4f after %.4f, fit before %.4f after %.4f, unexplained %d", name.c_str(),
              r.before.validationNrmse, r.after.validationNrmse, r.before.fitNrmse, r.after.fitNrmse, int(r.unexplained));
        // The baseline converged (issue 14 item 1): a fit stopped in a worse minimum fits its
        // own runs worse than its leave-one-run-out refits predict the held-out ones, the
        // signature IdentifyOptions::heldOutRestart detects and repairs (on D16 without it:
        // 0.1336 in-sample against 0.0996 held-out; docs/identify-results.md, session 13).
        if (!r.baselineNote.empty()) qInfo("%s: %s", name.c_str(), r.baselineNote.c_str());
        for (const AddedEffect& e : r.effectsAdded)
            if (!e.note.empty()) qInfo("%s: model with %s: %s", name.c_str(), e.name.c_str(), e.note.c_str());
        QVERIFY2(r.before.fitNrmse <= 1.1 * r.before.validationNrmse, "baseline in-sample error above its held-out error");
        // On a set without an effect the baseline is the whole model: its held-out error is at
        // the floor the answer key's own model reaches on the same runs (issue 14 item 1; measured
        // in session 14: D05 0.0239 / 0.0242, D10 0.0557 / 0.0548, D14 0.0347 / 0.0353, D16
        // 0.0432 / 0.0423, fitted / key).
        if (truth.empty()) {
            const ModelErrors key = truthErrors(name, runs);
            qInfo("%s: held-out NRMSE of the fitted baseline %.4f, of the answer key's model %.4f (ratio %.3f)", name.c_str(),
                  r.before.validationNrmse, key.validationNrmse, r.before.validationNrmse / key.validationNrmse);
            QVERIFY2(r.before.validationNrmse <= 1.05 * key.validationNrmse, "baseline held-out error above the key's floor");
            // And it converged: with every law parameter free it fits its own runs at least as
            // well as the key's model does. A baseline in a worse minimum can still meet the
            // held-out floor (its leave-one-run-out refits leave that minimum), as D16's did
            // before the restart from the candidates' points (sum of squares 169.1 against
            // 135.9 at the key's law; docs/identify-results.md, session 22).
            qInfo("%s: fit NRMSE of the fitted baseline %.4f, of the answer key's model %.4f", name.c_str(), r.before.fitNrmse,
                  key.fitNrmse);
            QVERIFY2(r.before.fitNrmse <= key.fitNrmse, "baseline fits its runs worse than the answer key's model");
        }
        // The final model converged too: a candidate of the last round whose size ended on the
        // bound where its effect vanishes is the final model at another point, so it cannot fit
        // the runs better (D06 in session 54: frictional_lag with tau on its lower bound, fit
        // NRMSE 0.0240 against the final model's 0.0320; polishFinalModel, session 55) unless
        // the final model refitted there predicted the held-out runs worse and was not kept
        // (FinalPolish; D18 in session 65): then the report says so, with both held-out errors.
        const int lastRound = static_cast<int>(r.effectsAdded.size()) + 1;
        const auto j = toJson(r);
        QCOMPARE(j.contains("final_polish"), r.polish.refitted);
        if (r.polish.refitted) {
            qInfo("%s: final polish %s: sum of squares %.4f -> %.4f, held-out NRMSE %.5f -> %.5f", name.c_str(),
                  r.polish.kept ? "kept" : "not kept", r.polish.ssBefore, r.polish.ssRefit, r.polish.heldOutBefore,
                  r.polish.heldOutRefit);
            QCOMPARE(j["final_polish"]["kept"].get<bool>(), r.polish.kept);
            QVERIFY(r.polish.ssRefit < r.polish.ssBefore);
            QCOMPARE(r.after.validationNrmse, r.polish.kept ? r.polish.heldOutRefit : r.polish.heldOutBefore);
            QCOMPARE(r.polish.kept, !(r.polish.heldOutRefit > r.polish.heldOutBefore));
        }
        for (const CandidateScore& c : r.candidates) {
            if (r.polish.refitted && !r.polish.kept) break;
            EffectInfo info;
            if (c.round != lastRound || c.accepted || c.residual != r.residual || !findEffect(c.name, info) ||
                info.params.empty())
                continue;
            const EffectParam& q = info.params.front();
            const std::string vanishing = q.vanishing >= q.upper ? "upper" : q.vanishing <= q.lower ? "lower" : "";
            if (vanishing.empty() || c.reason.find("ended on its physical " + vanishing + " bound") == std::string::npos)
                continue;
            qInfo("%s: %s ended where it vanishes at fit NRMSE %.5f; the final model's %.5f", name.c_str(), c.name.c_str(),
                  c.fitNrmse, r.after.fitNrmse);
            QVERIFY2(c.fitNrmse >= 0.99 * r.after.fitNrmse,
                     qPrintable(QString::fromStdString(c.name + " without its effect fits better than the final model")));
        }
        // Whatever it adds never makes the held-out error worse.
        QVERIFY(r.after.validationNrmse <= r.before.validationNrmse);
        std::set<std::string> got;
        for (const AddedEffect& e : r.effectsAdded) got.insert(e.name);
        QStringList want;
        for (const std::string& t : truth) want << QString::fromStdString(t);
        const auto miss = kKnownMiss.find(name);
        if (miss != kKnownMiss.end()) QEXPECT_FAIL("", miss->second, Continue);
        QVERIFY2(got == truth, qPrintable("added: [" + added(r) + "], key: [" + want.join(", ") + "]"));
        if (!r.effectsAdded.empty()) QVERIFY(r.after.validationNrmse < r.before.validationNrmse);
    }

    // The sanitizer pass's case of the loop above (scripts/sanitize.sh runs this instead of the
    // 18 full sets, which take 2-6 minutes each in Release): every stage of the loop
    // (preprocessing, baseline fit, each catalogue candidate's fit, the noise null, the held-out
    // check, the acceptance of an effect) on a smaller problem: 3 runs of D02 (key:
    // normal_load_mu) cut to 6 s, 40 noise replicas. The verdict is the full case's business;
    // this checks the loop's invariants: it ends ok, every candidate is scored, and an effect
    // it adds lowers the held-out error (measured: one added, 0.0748 -> 0.0217).
    void smallCaseRunsEveryStage() {
        IdentifyOptions opt;
        opt.nullReplicas = 40;
        opt.maxEffects = 1;
        const IdentifyResult r = identifySet("D02", opt, 3, 6.0);
        QVERIFY2(r.ok, r.message.c_str());
        qInfo("small D02: held-out NRMSE before %.4f after %.4f, %d effects added", r.before.validationNrmse,
              r.after.validationNrmse, int(r.effectsAdded.size()));
        QVERIFY(std::isfinite(r.before.fitNrmse) && r.before.fitNrmse > 0 && r.before.fitNrmse < 1);
        // Spring–mass runs: the warm-started fits move in the steady-state curve's coordinates.
        QCOMPARE(r.coordinates, std::string("steady_state_curve"));
        QCOMPARE(r.candidates.size(), effectCatalogue().size());
        for (const CandidateScore& c : r.candidates)
            QVERIFY2(c.accepted || !c.reason.empty(), c.name.c_str());
        QVERIFY(r.after.validationNrmse <= r.before.validationNrmse);
        if (!r.effectsAdded.empty()) QVERIFY(r.after.validationNrmse < r.before.validationNrmse);
    }

};

QTEST_APPLESS_MAIN(TstIdentifySynthetic)
#include "tst_identify_synthetic.moc"
