// The identify loop with its default options on sets made by `stickslip-cli synthesize`
// (core/identify/synthesize.hpp), written to disk and read back as a user's files are. The
// answer is known; the sets are not among those the loop was developed on.
//
// Seed 1 has no effect. On it the loop of session 38 added a viscous_damping whose ζ (0.0055)
// lay inside the rig's baseline range, i.e. the baseline itself in a better minimum, and after
// that was mended a 0.5 µm backlash that took up the part of the baseline's own minimum below
// the restart margin of 10 (docs/identify-results.md, session 39): neither may come back. Until
// session 41 it added a sensor mass of a few grams instead, on a baseline biased to C1 = 2.0 (its
// bound), η 3.45, v_c 0.40 against the true 0.212, 0.314, 0.103: the law channel was compared
// next to slip onsets and stops, where the filtered prediction blends model and measurement
// (IdentifyOptions::maskEdgeGuard). With the guard (off by default, see identify.hpp) nothing may
// be added and the baseline must be near the law the set was made with.
#include <QtTest/QtTest>

#include <map>
#include <set>

#include "core/identify/identify.hpp"
#include "core/identify/synthesize.hpp"
#include "core/io/csv_table.hpp"
#include "rig_set_loader.hpp"

using namespace stickslip;
using namespace stickslip::identify;

namespace {

// Writes the set of `o` into dir (runs and manifest, as the CLI does).
void writeSet(const SynthOptions& o, const QString& dir) {
    const SynthResult r = synthesizeRigSet(o);
    if (!r.ok) qFatal("%s", r.message.c_str());
    std::string err;
    for (const SynthRun& run : r.runs)
        if (!io::writeFileAtomically(dir.toStdString() + "/" + run.file, synthRunCsv(run), &err)) qFatal("%s", err.c_str());
    if (!io::writeFileAtomically(dir.toStdString() + "/manifest.json", r.manifest.dump(1), &err)) qFatal("%s", err.c_str());
}

// The runs of the set `o` describes, written to a temporary directory and read back as a user's
// files are (with `withRecordings`, each keeps its recording for the simulated null).
std::vector<IdentifyRun> writtenRuns(const SynthOptions& o, bool withRecordings = false) {
    QTemporaryDir dir;
    if (!dir.isValid()) qFatal("no temporary directory");
    writeSet(o, dir.path());
    return rigset::loadRuns(dir.path().toStdString(), o.runs, INFINITY, withRecordings);
}

}  // namespace

class TstIdentifySynthesized : public QObject {
    Q_OBJECT
private slots:
    void setWithoutEffectAddsNothing() {
        SynthOptions o;
        o.seed = 1;
        IdentifyOptions opt;
        opt.maskEdgeGuard = true;
        const IdentifyResult r = identifyEffects(writtenRuns(o), opt);
        QVERIFY2(r.ok, r.message.c_str());
        for (const CandidateScore& c : r.candidates)
            qInfo("%s round %d dBIC %.2f gain %.4g (own minimum %.4g, null %.4g): %s", c.name.c_str(), c.round, c.deltaBic,
                  c.gain, c.ownMinimumGain, c.nullGain, c.accepted ? "added" : c.reason.c_str());
        qInfo("held-out NRMSE before %.4f after %.4f; %s", r.before.validationNrmse, r.after.validationNrmse,
              r.baselineNote.c_str());
        QVERIFY2(r.effectsAdded.empty(), r.effectsAdded.empty() ? "" : r.effectsAdded.front().name.c_str());
        // The law the set was made with (answer.json of `synthesize --seed 1`).
        const SynthResult truth = synthesizeRigSet(o);
        const std::map<std::string, double> want = {{"mu", truth.truth.law.mu}, {"C1", truth.truth.law.C1},
                                                    {"eta", truth.truth.law.eta_s_per_m}, {"vc", truth.truth.law.vc_mps}};
        for (const ParamEstimate& p : r.baseline) {
            const auto w = want.find(p.name);
            if (w == want.end()) continue;
            const double rel = std::abs(p.value / w->second - 1.0);
            qInfo("%s %.4g (true %.4g, %.1f %%)", p.name.c_str(), p.value, w->second, 100.0 * rel);
            QVERIFY2(rel < (p.name == "mu" ? 0.01 : 0.25), p.name.c_str());
        }
    }

    // Seed 5 has no effect. The baseline's scans of D_c and ε_T ran once, in that order, so D_c was
    // chosen at the start's ε_T (1e6 N/m against the set's 1.6e4): the fit then stopped with D_c
    // = 4.4 mm, C1 0.027, η and v_c on their lower bounds, held-out NRMSE 0.072, twice the noise
    // level, and only a candidate's point in round 1 got the loop out (117 fits). With a second
    // pass of the scans the baseline alone is at the noise level (docs/identify-results.md,
    // session 46).
    void baselineAloneReachesTheNoiseLevel() {
        SynthOptions o;
        o.seed = 5;
        IdentifyOptions opt;
        opt.maxEffects = 0;
        const IdentifyResult r = identifyEffects(writtenRuns(o), opt);
        QVERIFY2(r.ok, r.message.c_str());
        qInfo("held-out NRMSE %.4f, fit %.4f; %s", r.before.validationNrmse, r.before.fitNrmse, r.baselineNote.c_str());
        for (const ParamEstimate& p : r.baseline) qInfo("%s %.4g", p.name.c_str(), p.value);
        QVERIFY2(r.before.validationNrmse < 0.045, std::to_string(r.before.validationNrmse).c_str());
    }

    // Seed 6 has no effect. With the default options (no edge guard) a sensor mass of 6.4 g passed
    // tests (1)-(3) through session 44: every held-out run better, but by 0.5 % of the MSE on
    // average. The relevance margin (IdentifyOptions::minHeldOutGain, test 2b) stops it, and the
    // candidate's row says so (docs/identify-results.md, session 45).
    void relevanceMarginStopsASliverOfStructure() {
        SynthOptions o;
        o.seed = 6;
        const IdentifyResult r = identifyEffects(writtenRuns(o), IdentifyOptions{});
        QVERIFY2(r.ok, r.message.c_str());
        bool stopped = false;
        for (const CandidateScore& c : r.candidates) {
            qInfo("%s round %d dBIC %.2f held-out mean log ratio %.4g: %s", c.name.c_str(), c.round, c.deltaBic,
                  c.heldOutMeanLogRatio, c.accepted ? "added" : c.reason.c_str());
            if (c.name == "sensor_inertia" && c.reason.find("below the relevance margin of 5 %") != std::string::npos) stopped = true;
        }
        QVERIFY2(r.effectsAdded.empty(), r.effectsAdded.empty() ? "" : r.effectsAdded.front().name.c_str());
        QVERIFY(stopped);
    }

    // Two effects at once (seed 206: a 35 µm backlash and viscous damping ζ = 0.1), made by our own
    // simulator with seeds the loop was never run on before session 47. Both must be added and
    // nothing else; eight such pairs were all exact (docs/identify-results.md, session 47).
    void twoEffectsAreBothFoundAndNothingElse() {
        SynthOptions o;
        o.seed = 206;
        o.effects = {{"backlash", {3.5e-5}}, {"viscous_damping", {0.1}}};
        const IdentifyResult r = identifyEffects(writtenRuns(o), IdentifyOptions{});
        QVERIFY2(r.ok, r.message.c_str());
        std::set<std::string> added;
        for (const AddedEffect& e : r.effectsAdded) added.insert(e.name);
        for (const CandidateScore& c : r.candidates)
            qInfo("%s round %d dBIC %.2f: %s", c.name.c_str(), c.round, c.deltaBic, c.accepted ? "added" : c.reason.c_str());
        qInfo("held-out NRMSE %.4f -> %.4f", r.before.validationNrmse, r.after.validationNrmse);
        QCOMPARE(added, (std::set<std::string>{"backlash", "viscous_damping"}));
        QVERIFY(r.after.validationNrmse < 0.5 * r.before.validationNrmse);
    }

    // The simulated null (IdentifyOptions::simulatedNullReplicas) runs through the whole chain on a
    // set with a real sensor mass (86 g, seed 108's size): replicas are made from the bias-corrected
    // current model, their gains are far below the real one, and the effect is added.
    void simulatedNullKeepsARealEffect() {
        SynthOptions o;
        o.seed = 108;
        o.runs = 3;
        o.seconds = 8.0;
        o.effects = {{"sensor_inertia", {0.086}}};
        IdentifyOptions opt;
        opt.candidates = {"sensor_inertia"};
        opt.simulatedNullReplicas = 2;
        opt.simulatedNullBiasSteps = 1;
        opt.reprepare = rigset::reprepare;
        const IdentifyResult r = identifyEffects(writtenRuns(o, true), opt);
        QVERIFY2(r.ok, r.message.c_str());
        QCOMPARE(r.candidates.size(), size_t{1});
        const CandidateScore& c = r.candidates.front();
        qInfo("gain %.4g, simulated null quantile %.4g (%s), %s", c.gain, c.simulatedNullGain, c.simulatedNullNote.c_str(),
              c.accepted ? "added" : c.reason.c_str());
        QCOMPARE(c.simulatedGains.size(), size_t{2});
        QVERIFY(c.simulatedNullModel.count("mu") && c.simulatedNullModel.count("C1"));
        QVERIFY(c.simulatedNullGain >= c.simulatedGains.back() && c.simulatedNullGain < c.gain);
        QVERIFY(c.accepted);
    }
};

QTEST_APPLESS_MAIN(TstIdentifySynthesized)
#include "tst_identify_synthesized.moc"
