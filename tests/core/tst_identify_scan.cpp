// The search for the lowest sum of squares behind the candidates' scanned starts and the restart
// guards (identify_residuals.cpp lowestSS, identify_fit.cpp scannedStart): a sum stopped once it
// passes the lowest full sum so far is a lower bound above it and never changes which point is
// lowest. Prescribed runs made by the project's own simulator (identify_synth.hpp).
#include <QtTest/QtTest>

#include <cmath>
#include <limits>

#include "core/identify/identify_internal.hpp"
#include "identify_synth.hpp"

using namespace stickslip;
using namespace stickslip::identify;
using namespace stickslip::identify::detail;

namespace {

struct Fixture {
    IdentifyOptions opt = synth::testOptions();
    std::vector<IdentifyRun> runs;
    Context cx;
    std::vector<size_t> idx;
    std::map<std::string, double> start;

    bool make(const ExtendedModel& truth, std::string& why) {
        runs = synth::makeRuns(truth, 1.5, 0.02, 3);
        int dec = 0;
        if (!prepareContext(runs, opt, cx, dec, why)) return false;
        for (size_t i = 0; i < runs.size(); ++i) idx.push_back(i);
        // The law at the truth's values: the scan then looks for the effect alone.
        start = {{"mu", truth.law.mu}, {"C1", truth.law.C1}, {"eta", truth.law.eta_s_per_m}, {"vc", truth.law.vc_mps}};
        return true;
    }
};

// Runs with a 4 ms frictional lag, and the model with that candidate.
struct LagFixture : Fixture {
    Spec spec;
    bool make(std::string& why) {
        ExtendedModel truth = synth::trueModel();
        truth.effects.frictionalLag = FrictionalLag{4e-3};
        spec.effects = {"frictional_lag"};
        return Fixture::make(truth, why);
    }
};

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

class TestIdentifyScan : public QObject {
    Q_OBJECT
private slots:
    // lowestSS answers as the exhaustive search does: the lowest full sum (ties: the first),
    // only below the bound; the full sums it reports are evalSS's to the last bit, and a point it
    // stopped early carries a partial sum that is a lower bound of its full one and above the
    // answer's.
    void lowestSSIsTheExhaustiveAnswer() {
        Fixture fx;
        std::string why;
        QVERIFY2(fx.make(synth::trueModel(), why), why.c_str());
        QCOMPARE(fx.idx.size(), size_t{4});
        const Spec spec;
        // The truth, points around it in μ and η, a duplicate of the truth, and a point that
        // cannot be evaluated.
        std::vector<std::map<std::string, double>> pts;
        for (double f : {1.3, 0.7, 1.0, 1.6, 0.9, 1.0, 2.5, 1.05}) {
            std::map<std::string, double> v = fx.start;
            v["mu"] *= f;
            v["eta"] *= 2.0 - f * 0.5;
            pts.push_back(v);
        }
        pts[5] = pts[2];
        pts.push_back(fx.start);
        pts.back()["mu"] = std::numeric_limits<double>::quiet_NaN();
        std::vector<double> full;
        for (const auto& v : pts) full.push_back(evalSS(fx.cx, spec, v, fx.idx));
        int exhaustive = -1;
        for (size_t k = 0; k < full.size(); ++k)
            if (std::isfinite(full[k]) && (exhaustive < 0 || full[k] < full[static_cast<size_t>(exhaustive)]))
                exhaustive = static_cast<int>(k);
        QVERIFY(exhaustive >= 0);
        QVERIFY(!std::isfinite(full.back()) || full.back() > full[static_cast<size_t>(exhaustive)]);
        std::vector<double> sums;
        const int got = lowestSS(fx.cx, spec, pts, fx.idx, kInf, &sums);
        qInfo("exhaustive: point %d at %.6g; lowestSS: point %d", exhaustive, full[static_cast<size_t>(exhaustive)], got);
        QCOMPARE(got, exhaustive);
        QCOMPARE(got, 2);  // the truth, not its later duplicate
        QCOMPARE(sums[2], full[2]);
        int stopped = 0;
        for (size_t k = 0; k < pts.size(); ++k) {
            if (sums[k] == full[k]) continue;
            ++stopped;
            QVERIFY(sums[k] <= full[k] || !std::isfinite(full[k]));
            QVERIFY(sums[k] > full[2]);
        }
        qInfo("%d of %zu points stopped before their last run", stopped, pts.size());
        QVERIFY(stopped > 0);
        // A bound: only a point strictly below it counts.
        QCOMPARE(lowestSS(fx.cx, spec, pts, fx.idx, full[2]), -1);
        QCOMPARE(lowestSS(fx.cx, spec, pts, fx.idx, std::nextafter(full[2], kInf)), 2);
        // One run, and no point at all.
        QCOMPARE(lowestSS(fx.cx, spec, pts, {fx.idx[1]}), 2);
        QCOMPARE(lowestSS(fx.cx, spec, {}, fx.idx), -1);
    }

    // The scan keeps the lowest of its points by their full sums: the point it returns fits at
    // least as well as every value of the effect's own grid (9 log values across its range) and
    // its start, each evaluated in full here, although the scan abandoned most of them early.
    void scannedStartKeepsTheLowestFullSum() {
        LagFixture fx;
        std::string why;
        QVERIFY2(fx.make(why), why.c_str());
        const Spec& spec = fx.spec;
        const std::map<std::string, double> st = scannedStart(fx.cx, spec, "frictional_lag", fx.start, fx.idx);
        const double chosen = evalSS(fx.cx, spec, st, fx.idx);
        QVERIFY(std::isfinite(chosen));
        EffectInfo info;
        QVERIFY(findEffect("frictional_lag", info));
        const EffectParam q = scaledParam(info.params.front(), fx.cx.muScale);
        const std::string key = "frictional_lag." + q.name;
        std::map<std::string, double> v = effectStart(fx.cx, "frictional_lag", fx.start);
        double lowest = evalSS(fx.cx, spec, v, fx.idx);
        for (int k = 0; k < 9; ++k) {
            v[key] = q.lower * std::pow(q.upper / q.lower, k / 8.0);
            lowest = std::min(lowest, evalSS(fx.cx, spec, v, fx.idx));
        }
        qInfo("scan chose tau = %.3g s at SS %.6g; lowest of the grid in full %.6g", st.at(key), chosen, lowest);
        QCOMPARE(chosen, lowest);
        // And it is one of the two grid values around the truth's 4 ms (within one log step).
        QVERIFY(std::abs(std::log(st.at(key) / 4e-3)) <= std::log(q.upper / q.lower) / 8.0 + 1e-12);
    }

    // After a restart the candidate's earlier fit competes with the scan: it is the start when it
    // fits the runs better, and the scanned point otherwise (and on a tie).
    void previousFitIsTheStartOnlyWhenItFitsBetter() {
        LagFixture fx;
        std::string why;
        QVERIFY2(fx.make(why), why.c_str());
        const Spec& spec = fx.spec;
        const std::map<std::string, double> scanned = scannedStart(fx.cx, spec, "frictional_lag", fx.start, fx.idx);
        const std::string key = "frictional_lag." + [] {
            EffectInfo info;
            findEffect("frictional_lag", info);
            return info.params.front().name;
        }();
        // The truth itself (τ = 4 ms exactly) fits better than the scan's grid value.
        std::map<std::string, double> better = scanned;
        better[key] = 4e-3;
        const double ssScan = evalSS(fx.cx, spec, scanned, fx.idx), ssBetter = evalSS(fx.cx, spec, better, fx.idx);
        QVERIFY2(ssBetter < ssScan, qPrintable(QString("%1 vs %2").arg(ssBetter).arg(ssScan)));
        QCOMPARE(scannedStart(fx.cx, spec, "frictional_lag", fx.start, fx.idx, &better), better);
        // A far worse earlier point (μ off by 30 %) loses to the scan, and so does an equal one.
        std::map<std::string, double> worse = better;
        worse["mu"] *= 1.3;
        QVERIFY(evalSS(fx.cx, spec, worse, fx.idx) > ssScan);
        QCOMPARE(scannedStart(fx.cx, spec, "frictional_lag", fx.start, fx.idx, &worse), scanned);
        QCOMPARE(scannedStart(fx.cx, spec, "frictional_lag", fx.start, fx.idx, &scanned), scanned);
    }

    // evalSSRefined (law_resolution.cpp), the sum behind an added effect's law-step check: at
    // refinement 1 it is evalSS to the last bit; split finer, it is the same runs' sum with the
    // law run at the finer step (here a stiff, stable contact: close to it, but not the same
    // numbers); the segment residual has no law channel of its own (NaN).
    void refinedSumIsEvalSSAtRefinementOne() {
        Fixture fx;
        std::string why;
        QVERIFY2(fx.make(synth::trueModel(), why), why.c_str());
        const Spec spec;
        const double ss = evalSS(fx.cx, spec, fx.start, fx.idx);
        QVERIFY(std::isfinite(ss) && ss > 0);
        QCOMPARE(evalSSRefined(fx.cx, spec, fx.start, fx.idx, 1), ss);
        QCOMPARE(evalSSRefined(fx.cx, spec, fx.start, fx.idx, 0), ss);
        const double fine = evalSSRefined(fx.cx, spec, fx.start, fx.idx, kLawResolutionRefinement);
        QVERIFY2(std::isfinite(fine) && fine != ss && std::abs(fine - ss) < 0.5 * ss,
                 qPrintable(QString("%1 vs %2").arg(fine).arg(ss)));
        Spec seg;
        seg.segments = true;
        QVERIFY(std::isnan(evalSSRefined(fx.cx, seg, fx.start, fx.idx, kLawResolutionRefinement)));
    }
};

QTEST_APPLESS_MAIN(TestIdentifyScan)
#include "tst_identify_scan.moc"
