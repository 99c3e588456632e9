#include <QtTest>

#include "core/integrate/simulate.hpp"
#include "core/presets.hpp"

using namespace stickslip;

class TstSmoke : public QObject {
    Q_OBJECT
private slots:
    void fig20RunsAndSlips() {
        Preset p;
        QVERIFY(findPreset("default", p));
        p.params.cycles = 5;
        const RunResult r = simulate(p.params);
        QVERIFY2(r.ok(), r.message.c_str());
        QVERIFY(r.samples.size() > 100);
        bool slipped = false;
        for (const auto& s : r.samples) slipped |= !s.stuck;
        QVERIFY(slipped);
    }
};

QTEST_GUILESS_MAIN(TstSmoke)
#include "tst_smoke.moc"
