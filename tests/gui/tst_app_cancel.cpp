// The app's long jobs that had no cancel test reach the core's flag: a periodicity map
// started from its dialog stops on Cancel with the cells finished so far, and a long single
// run stops on "Cancel all jobs" without delivering a result. (Sweep, fit and identify are
// covered in tst_app_sweep and tst_identify_panel; the CLI's SIGINT in tests/cli/tst_cli_cancel.)
// The bounds here are generous; latencies are figures of bench_memory --cancel, not checks.
#include <QPushButton>
#include <QSignalSpy>
#include <QtTest>

#include "core/presets.hpp"
#include "model_fixtures.hpp"
#include "simulation_controller.hpp"
#include "sweep_dialogs.hpp"

using namespace stickslip;
using namespace stickslip::gui;

using stickslip::gui::test::fig20;

class TstAppCancel : public QObject {
    Q_OBJECT
private slots:
    void mapDialogCancelStopsTheMap() {
        SimulationController c;
        MapDialog dialog(&c, [] { return fig20(); });
        const MapOptions o = dialog.options();
        QVERIFY(o.validate(fig20().params).empty());
        QSignalSpy finished(&c, &SimulationController::mapFinished);
        dialog.runButton()->click();
        QTest::qWait(500);
        QVERIFY2(c.isBusy(JobKind::Map), "the dialog's default map must take longer than 0.5 s");
        QVERIFY(dialog.cancelButton()->isEnabled());
        dialog.cancelButton()->click();
        QVERIFY(finished.wait(15000));
        const auto out = finished.at(0).at(0).value<MapOutcome>();
        QVERIFY(out.map.status == RunStatus::Cancelled);
        size_t done = 0;
        for (auto d : out.map.done) done += d ? 1 : 0;
        QVERIFY2(done < out.map.done.size(), qPrintable(QString::number(done)));
        QVERIFY(!c.isBusy(JobKind::Map));
        QVERIFY2(dialog.statusText().startsWith("Cancelled"), qPrintable(dialog.statusText()));
        QCOMPARE(c.cancelledCount(JobKind::Map), 1);
    }

    void cancelAllStopsALongRun() {
        SimulationController c;
        c.setPoincareEnabled(false);
        QSignalSpy done(&c, &SimulationController::runFinished);
        ModelSettings s = fig20();
        s.params.cycles = 100000;  // minutes of work
        QVERIFY(s.params.validate().empty());
        c.requestRun(s);
        QTest::qWait(300);
        QVERIFY(c.isBusy(JobKind::Run));
        c.cancelAll();
        QTRY_VERIFY_WITH_TIMEOUT(c.isIdle(), 15000);
        QCOMPARE(c.cancelledCount(JobKind::Run), 1);
        QCOMPARE(done.count(), 0);  // a cancelled run delivers nothing
    }
};

QTEST_MAIN(TstAppCancel)
#include "tst_app_cancel.moc"
