// Cell-level map and independent-sweep API (what MPI ranks and checkpoint resume use):
// computing cells / values in interleaved subsets, in any order, and assembling them gives
// exactly (bitwise) the one-call result; callbacks, out-of-range indices and bad options.
#include <QtTest>

#include <cmath>
#include <cstring>
#include <mutex>

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
MapOptions smallMap() {
    MapOptions o;
    o.key1 = "A";
    o.from1 = 0.2e-3;
    o.to1 = 2.0e-3;
    o.steps1 = 4;
    o.key2 = std::string("tN");
    o.from2 = 3.0;
    o.to2 = 8.0;
    o.steps2 = 3;
    o.settleCycles = 6;
    o.sampleCycles = 8;
    o.stepsPerPeriod = 1000;
    o.threads = 2;
    return o;
}
SweepOptions smallSweep() {
    SweepOptions o;
    o.key = std::string("A");
    o.from = 1.0e-3;
    o.to = 0.2e-3;
    o.steps = 5;
    o.mode = SweepMode::Independent;
    o.direction = SweepDirection::Both;
    o.settleCycles = 6;
    o.sampleCycles = 6;
    o.stepsPerPeriod = 1000;
    o.threads = 2;
    return o;
}
template <class T>
bool bitwiseEqual(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}
bool bitwiseEqual(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool samePoint(const SweepPoint& p, const SweepPoint& q) {
    return bitwiseEqual(p.value, q.value) && p.direction == q.direction &&
           bitwiseEqual(p.section.t_s, q.section.t_s) && bitwiseEqual(p.section.slider_m, q.section.slider_m) &&
           bitwiseEqual(p.section.relVel_mps, q.section.relVel_mps) && bitwiseEqual(p.section.ratio, q.section.ratio) &&
           bitwiseEqual(p.section.alpha, q.section.alpha) &&
           bitwiseEqual(p.section.stickFraction, q.section.stickFraction) &&
           bitwiseEqual(p.section.maxRelVel_mps, q.section.maxRelVel_mps) &&
           p.classification.motion == q.classification.motion && p.classification.period == q.classification.period &&
           bitwiseEqual(p.lyapunovPerCycle, q.lyapunovPerCycle) && bitwiseEqual(p.lyapunovPerSecond, q.lyapunovPerSecond);
}
}  // namespace

class TstAnalysisCells : public QObject {
    Q_OBJECT
private slots:
    void mapCellsInSubsetsAssembleBitwise() {
        const MapOptions o = smallMap();
        QCOMPARE(mapCellCount(o), std::size_t(12));
        const PeriodicityMap whole = periodicityMap(fig20(), o);
        QVERIFY2(whole.ok(), whole.message.c_str());
        // Three interleaved subsets, each listed backwards, assembled in a shuffled order.
        std::vector<MapCell> all;
        std::mutex m;
        int callbacks = 0;
        for (std::size_t r : {2u, 0u, 1u}) {
            std::vector<std::size_t> idx;
            for (std::size_t i = r; i < 12; i += 3) idx.insert(idx.begin(), i);
            const auto cells = periodicityMapCells(fig20(), o, idx, {}, [&](const MapCell& c) {
                std::lock_guard<std::mutex> lk(m);  // already serialised by the callee; checks no deadlock
                QVERIFY(c.status == RunStatus::Ok);
                ++callbacks;
            });
            QCOMPARE(cells.size(), idx.size());
            for (std::size_t k = 0; k < idx.size(); ++k) QCOMPARE(cells[k].index, idx[k]);
            all.insert(all.end(), cells.begin(), cells.end());
        }
        QCOMPARE(callbacks, 12);
        const PeriodicityMap parts = assemblePeriodicityMap(fig20(), o, all);
        QVERIFY(parts.ok());
        QVERIFY(bitwiseEqual(parts.values1, whole.values1) && bitwiseEqual(parts.values2, whole.values2));
        QVERIFY(bitwiseEqual(parts.motion, whole.motion));
        QVERIFY(bitwiseEqual(parts.period, whole.period));
        QVERIFY(bitwiseEqual(parts.stickFraction, whole.stickFraction));
        QVERIFY(bitwiseEqual(parts.maxRelVel_mps, whole.maxRelVel_mps));
        QVERIFY(bitwiseEqual(parts.done, whole.done));
        // A missing cell makes the assembled map Cancelled with that cell not done.
        all.erase(all.begin());
        const PeriodicityMap partial = assemblePeriodicityMap(fig20(), o, all);
        QVERIFY(partial.status == RunStatus::Cancelled);
        int notDone = 0;
        for (auto d : partial.done) notDone += d ? 0 : 1;
        QCOMPARE(notDone, 1);
    }
    void mapCellsRejectBadInput() {
        MapOptions o = smallMap();
        const auto out = periodicityMapCells(fig20(), o, {12});
        QCOMPARE(out.size(), std::size_t(1));
        QVERIFY(out[0].status == RunStatus::Failed);
        const MapCell failed{3, RunStatus::Failed, MotionClass::Irregular, 0, 0, 0, "A = 1, tN = 2: boom"};
        const PeriodicityMap f = assemblePeriodicityMap(fig20(), o, {failed});
        QVERIFY(f.status == RunStatus::Failed);
        QCOMPARE(QString::fromStdString(f.message), QString("A = 1, tN = 2: boom"));
        o.key2 = std::string("A");
        const auto bad = periodicityMapCells(fig20(), o, {0});
        QVERIFY(bad[0].status == RunStatus::Failed && !bad[0].message.empty());
        QVERIFY(assemblePeriodicityMap(fig20(), o, bad).status == RunStatus::Failed);
        o.steps2 = 0;
        QCOMPARE(mapCellCount(o), std::size_t(0));
    }
    void independentSweepValuesAssembleBitwise() {
        for (bool lyapunov : {false, true}) {
            SweepOptions o = smallSweep();
            o.lyapunov = lyapunov;
            const SweepResult whole = bifurcationSweep(fig20(), o);
            QVERIFY2(whole.ok(), whole.message.c_str());
            QCOMPARE(whole.points.size(), std::size_t(10));
            std::vector<SweepValueRecord> all;
            int callbacks = 0;
            for (std::size_t r : {1u, 0u}) {
                std::vector<std::size_t> idx;
                for (std::size_t i = r; i < 5; i += 2) idx.push_back(i);
                const auto recs = independentSweepValues(fig20(), o, idx, {}, [&](const SweepValueRecord& rec) {
                    QVERIFY(rec.done);
                    ++callbacks;
                });
                all.insert(all.end(), recs.begin(), recs.end());
            }
            QCOMPARE(callbacks, 5);
            const SweepResult parts = assembleIndependentSweep(fig20(), o, all);
            QVERIFY(parts.ok());
            QCOMPARE(parts.points.size(), whole.points.size());
            for (std::size_t i = 0; i < whole.points.size(); ++i) QVERIFY(samePoint(parts.points[i], whole.points[i]));
            all.pop_back();
            QVERIFY(assembleIndependentSweep(fig20(), o, all).status == RunStatus::Cancelled);
        }
    }
    void independentSweepValuesRejectBadInput() {
        SweepOptions o = smallSweep();
        const auto out = independentSweepValues(fig20(), o, {5});
        QVERIFY(out[0].done && out[0].point.section.status == RunStatus::Failed);
        QVERIFY(assembleIndependentSweep(fig20(), o, out).status == RunStatus::Cancelled);  // index 5 ignored
        o.steps = 0;
        QVERIFY(assembleIndependentSweep(fig20(), o, {}).status == RunStatus::Failed);
    }
};

QTEST_GUILESS_MAIN(TstAnalysisCells)
#include "tst_analysis_cells.moc"
