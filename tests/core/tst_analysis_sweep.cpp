// Bifurcation sweeps (continuation and independent), the parallel loop and the 2-D map:
// determinism across thread counts, progress, cancel, directions and failures.
#include <QtTest>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>

#include "core/analysis/parallel.hpp"
#include "core/analysis/periodicity_map.hpp"
#include "core/analysis/sweep.hpp"
#include "core/presets.hpp"

using namespace stickslip;

namespace {
SimParams fig20() {
    Preset p;
    if (!findPreset("fig20", p)) qFatal("no fig20");
    return p.params;
}
SweepOptions small() {
    SweepOptions o;
    o.key = std::string("A");
    o.from = 0.2e-3;
    o.to = 1.0e-3;
    o.steps = 5;
    o.settleCycles = 6;
    o.sampleCycles = 6;
    o.stepsPerPeriod = 1000;
    return o;
}
bool samePoints(const SweepResult& a, const SweepResult& b) {
    if (a.points.size() != b.points.size()) return false;
    for (std::size_t i = 0; i < a.points.size(); ++i) {
        const auto &p = a.points[i], &q = b.points[i];
        if (p.value != q.value || p.direction != q.direction) return false;
        if (p.section.slider_m != q.section.slider_m || p.section.relVel_mps != q.section.relVel_mps ||
            p.section.ratio != q.section.ratio || p.section.stickFraction != q.section.stickFraction)
            return false;
        if (std::isnan(p.lyapunovPerCycle) != std::isnan(q.lyapunovPerCycle)) return false;
        if (!std::isnan(p.lyapunovPerCycle) && p.lyapunovPerCycle != q.lyapunovPerCycle) return false;
    }
    return true;
}
}  // namespace

class TstAnalysisSweep : public QObject {
    Q_OBJECT
private slots:
    void sweepValuesIncludeEndpoints() {
        const auto v = sweepValues(0.1, 0.5, 5);
        QCOMPARE(v.size(), std::size_t(5));
        QCOMPARE(v.front(), 0.1);
        QCOMPARE(v.back(), 0.5);
        QVERIFY(std::abs(v[2] - 0.3) < 1e-15);
        QCOMPARE(sweepValues(2.0, 3.0, 1), std::vector<double>{2.0});
        QVERIFY(sweepValues(0, 1, 0).empty());
        SweepMode m;
        SweepDirection d;
        QVERIFY(parseSweepMode("independent", m) && m == SweepMode::Independent);
        QVERIFY(parseSweepDirection("both", d) && d == SweepDirection::Both);
        QVERIFY(!parseSweepDirection("sideways", d));
        QCOMPARE(QString(toString(SweepDirection::Down)), QString("down"));
        QCOMPARE(QString(toString(SweepMode::Continuation)), QString("continuation"));
    }
    void parallelForVisitsEveryIndexOnce() {
        for (int threads : {1, 2, 4}) {
            std::vector<int> hits(97, 0);
            parallelFor(hits.size(), threads, [&](std::size_t i) { hits[i] += 1; });
            for (int h : hits) QCOMPARE(h, 1);
        }
        QCOMPARE(workerCount(4, 2), 2);
        QVERIFY(workerCount(0, 100) >= 1);
        std::atomic<int> ran{0};
        parallelFor(50, 2, [&](std::size_t) { ++ran; }, [] { return true; });
        QCOMPARE(ran.load(), 0);
    }
    void parallelForReportingReportsEachIndexOnceInOrderOfProgress() {
        for (int threads : {1, 2, 4}) {
            std::vector<int> body(61, 0), done(61, 0);
            std::vector<double> fractions;  // done/progress run under one lock: plain containers are safe
            parallelForReporting(
                body.size(), threads, [&](std::size_t i) { body[i] += 1; },
                [&](std::size_t i) {
                    QCOMPARE(body[i], 1);  // reported after its body ran
                    done[i] += 1;
                },
                [&](double f) { fractions.push_back(f); });
            for (std::size_t i = 0; i < body.size(); ++i) QVERIFY(body[i] == 1 && done[i] == 1);
            QCOMPARE(fractions.size(), body.size());
            for (std::size_t k = 0; k < fractions.size(); ++k)
                QCOMPARE(fractions[k], static_cast<double>(k + 1) / static_cast<double>(body.size()));
        }
        std::atomic<int> ran{0};  // stop is honoured; empty reporters are allowed
        parallelForReporting(20, 2, [&](std::size_t) { ++ran; }, nullptr, nullptr, [] { return true; });
        QCOMPARE(ran.load(), 0);
    }
    void independentSweepIsBitIdenticalForAnyThreadCount() {
        SweepOptions o = small();
        o.mode = SweepMode::Independent;
        o.lyapunov = true;
        o.threads = 1;
        const SweepResult r1 = bifurcationSweep(fig20(), o);
        QVERIFY2(r1.ok(), r1.message.c_str());
        QCOMPARE(r1.points.size(), std::size_t(5));
        o.threads = 2;
        const SweepResult r2 = bifurcationSweep(fig20(), o);
        o.threads = 4;
        const SweepResult r4 = bifurcationSweep(fig20(), o);
        QVERIFY(samePoints(r1, r2));
        QVERIFY(samePoints(r1, r4));
        // Stick at 0.2 mm (below A_s ≈ 0.33 mm), slip at 1 mm.
        QVERIFY(r1.points.front().classification.motion == MotionClass::Stick);
        QVERIFY(r1.points.back().classification.motion != MotionClass::Stick);
        QVERIFY(!std::isnan(r1.points.back().lyapunovPerSecond));
        QCOMPARE(r1.points.front().section.size(), std::size_t(6));
    }
    void continuationBothDirectionsCarriesState() {
        SweepOptions o = small();
        o.direction = SweepDirection::Both;
        std::vector<double> progress;
        RunControl ctl;
        ctl.progress = [&](double f) { progress.push_back(f); };
        const SweepResult r = bifurcationSweep(fig20(), o, ctl);
        QVERIFY2(r.ok(), r.message.c_str());
        QCOMPARE(r.points.size(), std::size_t(10));
        QCOMPARE(r.points[0].value, 0.2e-3);
        QCOMPARE(r.points[4].value, 1.0e-3);
        QCOMPARE(r.points[5].value, 1.0e-3);
        QCOMPARE(r.points[5].direction, -1);
        QCOMPARE(r.points[9].value, 0.2e-3);
        QCOMPARE(progress.size(), std::size_t(10));
        QCOMPARE(progress.back(), 1.0);
        for (const auto& p : r.points) QVERIFY(std::isnan(p.lyapunovPerCycle));
        // The first down value continues from the last up state: its first section point is
        // one settle+sample run later than the up branch's last point, from a different start
        // than rest — so it differs from the independent run at the same value.
        SweepOptions ind = small();
        ind.mode = SweepMode::Independent;
        const SweepResult fromRest = bifurcationSweep(fig20(), ind);
        QVERIFY(fromRest.ok());
        QVERIFY(r.points[5].section.slider_m != fromRest.points[4].section.slider_m);
        // Down only: descending order.
        o.direction = SweepDirection::Down;
        const SweepResult d = bifurcationSweep(fig20(), o);
        QVERIFY(d.ok());
        QCOMPARE(d.points.front().value, 1.0e-3);
        QCOMPARE(d.points.front().direction, -1);
    }
    // Concurrent branches: the down branch starts from rest at the top value (after a lead-in)
    // so the branches run at once. Same result on one thread or two; the up branch is the
    // sequential sweep's; the down branch still carries its state and, on this set, ends in the
    // same classes as the sequential down branch.
    void concurrentBranchesMatchSequentialOnes() {
        SweepOptions o = small();
        o.direction = SweepDirection::Both;
        const SweepResult seq = bifurcationSweep(fig20(), o);
        QVERIFY2(seq.ok(), seq.message.c_str());
        o.concurrentBranches = true;
        o.threads = 1;
        const SweepResult c1 = bifurcationSweep(fig20(), o);
        QVERIFY2(c1.ok(), c1.message.c_str());
        o.threads = 2;
        std::mutex m;
        std::vector<double> progress;
        RunControl ctl;
        ctl.progress = [&](double f) { std::lock_guard<std::mutex> lk(m); progress.push_back(f); };
        const SweepResult c2 = bifurcationSweep(fig20(), o, ctl);
        QVERIFY2(c2.ok(), c2.message.c_str());
        QVERIFY(samePoints(c1, c2));
        QCOMPARE(progress.size(), std::size_t(10));
        QCOMPARE(*std::max_element(progress.begin(), progress.end()), 1.0);
        QCOMPARE(c2.points.size(), std::size_t(10));
        // Layout as the sequential sweep: up ascending, then down descending.
        for (std::size_t i = 0; i < 10; ++i) {
            QCOMPARE(c2.points[i].value, seq.points[i].value);
            QCOMPARE(c2.points[i].direction, seq.points[i].direction);
        }
        // The up branch is the sequential one, bit for bit.
        SweepResult seqUp = seq, cUp = c2;
        seqUp.points.resize(5);
        cUp.points.resize(5);
        QVERIFY(samePoints(seqUp, cUp));
        // The down branch starts elsewhere (rest + lead-in, not the up branch's end state) ...
        QVERIFY(c2.points[5].section.slider_m != seq.points[5].section.slider_m);
        // ... but lands in the same classes, with nearly the same stick fractions.
        for (std::size_t i = 5; i < 10; ++i) {
            const auto &a = seq.points[i].classification, &b = c2.points[i].classification;
            QVERIFY2(a.motion == b.motion && a.period == b.period,
                     qPrintable(QString("A = %1 mm: %2%3 vs %4%5")
                                    .arg(seq.points[i].value * 1e3)
                                    .arg(toString(a.motion)).arg(a.period)
                                    .arg(toString(b.motion)).arg(b.period)));
            QVERIFY(std::abs(a.stickFraction - b.stickFraction) < 0.01);
        }
        // Each branch carries its state: below the top, the concurrent down branch is neither
        // the independent (from rest) run nor the up branch at the same value.
        SweepOptions ind = small();
        ind.mode = SweepMode::Independent;
        const SweepResult fromRest = bifurcationSweep(fig20(), ind);
        QVERIFY(fromRest.ok());
        bool historyShows = false;
        for (std::size_t k = 1; k < 5; ++k) {  // value index k from the top, down point 5 + k
            const SweepPoint& d = c2.points[5 + k];
            const SweepPoint& u = c2.points[4 - k];
            QCOMPARE(d.value, u.value);
            if (d.classification.motion == MotionClass::Stick) continue;
            QVERIFY(d.section.slider_m != fromRest.points[4 - k].section.slider_m);
            if (std::abs(d.classification.stickFraction - u.classification.stickFraction) > 0.005) historyShows = true;
        }
        QVERIFY(historyShows);
        // Cancel stops both branches.
        std::atomic<bool> cancel{true};
        RunControl stop;
        stop.cancel = &cancel;
        const SweepResult cancelled = bifurcationSweep(fig20(), o, stop);
        QVERIFY(cancelled.status == RunStatus::Cancelled);
        QVERIFY(cancelled.points.empty());
        // Only meaningful for both directions: up alone is unchanged.
        o.direction = SweepDirection::Up;
        const SweepResult upOnly = bifurcationSweep(fig20(), o);
        QVERIFY(samePoints(upOnly, seqUp));
    }
    // The Lyapunov companion on a second thread (continuation, one branch at a time) gives the
    // same points as on one thread.
    void continuationLyapunovIsThreadIndependent() {
        SweepOptions o = small();
        o.direction = SweepDirection::Both;
        o.lyapunov = true;
        o.threads = 1;
        const SweepResult r1 = bifurcationSweep(fig20(), o);
        QVERIFY2(r1.ok(), r1.message.c_str());
        o.threads = 2;
        const SweepResult r2 = bifurcationSweep(fig20(), o);
        QVERIFY2(r2.ok(), r2.message.c_str());
        QCOMPARE(r2.points.size(), std::size_t(10));
        QVERIFY(samePoints(r1, r2));
        QVERIFY(!std::isnan(r2.points[4].lyapunovPerCycle));
        QVERIFY(r2.points[4].section.size() == std::size_t(6));
    }
    void sweepOfAnotherKeyChangesTheDrive() {
        SweepOptions o = small();
        o.key = std::string("f");
        o.from = 3.0;
        o.to = 6.0;
        o.steps = 2;
        const SweepResult r = bifurcationSweep(fig20(), o);
        QVERIFY2(r.ok(), r.message.c_str());
        QCOMPARE(r.points[1].section.period_s, 1.0 / 6.0);
    }
    void sweepCancelAndBadOptions() {
        std::atomic<bool> cancel{true};
        RunControl ctl;
        ctl.cancel = &cancel;
        SweepOptions o = small();
        SweepResult r = bifurcationSweep(fig20(), o, ctl);
        QVERIFY(r.status == RunStatus::Cancelled);
        o.mode = SweepMode::Independent;
        r = bifurcationSweep(fig20(), o, ctl);
        QVERIFY(r.status == RunStatus::Cancelled);
        QVERIFY(r.points.empty());
        SweepOptions bad = small();
        bad.key = std::string("nonsense");
        bad.steps = 0;
        r = bifurcationSweep(fig20(), bad);
        QVERIFY(r.status == RunStatus::Failed);
        QVERIFY(r.message.find("nonsense") != std::string::npos);
        QVERIFY(r.message.find("steps") != std::string::npos);
        SweepOptions neg = small();
        neg.key = std::string("tN");
        neg.from = -1;
        r = bifurcationSweep(fig20(), neg);
        QVERIFY(r.status == RunStatus::Failed);
        QVERIFY(r.message.find("tN") != std::string::npos);
    }
    void periodicityMapIsThreadIndependent() {
        MapOptions o;
        o.key1 = "A";
        o.from1 = 0.2e-3;
        o.to1 = 1.0e-3;
        o.steps1 = 3;
        o.key2 = std::string("tN");
        o.from2 = 4.0;
        o.to2 = 8.0;
        o.steps2 = 2;
        o.settleCycles = 6;
        o.sampleCycles = 6;
        o.stepsPerPeriod = 1000;
        o.threads = 1;
        std::mutex m;
        int calls = 0;
        RunControl ctl;
        ctl.progress = [&](double) { std::lock_guard<std::mutex> lk(m); ++calls; };
        const PeriodicityMap a = periodicityMap(fig20(), o, ctl);
        QVERIFY2(a.ok(), a.message.c_str());
        QCOMPARE(calls, 6);
        QCOMPARE(a.motion.size(), std::size_t(6));
        QCOMPARE(a.index(2, 1), std::size_t(5));
        for (auto d : a.done) QCOMPARE(int(d), 1);
        // Low A, high t_N: stick. High A, low t_N: slip.
        QVERIFY(a.motion[a.index(0, 1)] == MotionClass::Stick);
        QVERIFY(a.motion[a.index(2, 0)] != MotionClass::Stick);
        o.threads = 2;
        const PeriodicityMap b = periodicityMap(fig20(), o);
        QVERIFY(a.period == b.period);
        QVERIFY(a.stickFraction == b.stickFraction);
        QVERIFY(a.maxRelVel_mps == b.maxRelVel_mps);
        o.key2 = std::string("A");
        const PeriodicityMap bad = periodicityMap(fig20(), o);
        QVERIFY(bad.status == RunStatus::Failed);
    }
};

QTEST_GUILESS_MAIN(TstAnalysisSweep)
#include "tst_analysis_sweep.moc"
