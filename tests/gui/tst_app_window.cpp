// The real main window, offscreen: a slider change reaches the plots (compared with a direct
// core run), presets switch, failures are reported in words, every view exports to PNG, SVG,
// PDF and CSV, a measured CSV is overlaid by column name, several dropped CSVs open the Identify
// import, and a session round-trips.
#include <QComboBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QApplication>
#include <QDropEvent>
#include <QFile>
#include <QMimeData>
#include <QScreen>
#include <QSignalSpy>
#include <QSlider>
#include <QTabBar>
#include <QTemporaryDir>
#include <QTimer>
#include <QtTest>
#include <qwt_plot_curve.h>
#include <cmath>

#include "command_line.hpp"
#include "import_dialog.hpp"
#include "core/integrate/simulate.hpp"
#include "main_window.hpp"
#include "parameter_panel.hpp"
#include "param_specs.hpp"
#include "session.hpp"
#include "simulation_controller.hpp"
#include "view_set.hpp"
#include "widgets/friction_loop_plot.hpp"
#include "widgets/phase_portrait_plot.hpp"
#include "widgets/poincare_plot.hpp"
#include "widgets/time_series_plot.hpp"

using namespace stickslip;
using namespace stickslip::gui;

namespace {

// Waits (generously: CI also runs this under ASan) for a shown run whose parameters satisfy pred.
template <class Pred>
bool waitForRun(MainWindow& w, Pred pred, RunOutcome* out = nullptr, int timeout_ms = 120000) {
    QSignalSpy spy(&w, &MainWindow::runShown);
    QElapsedTimer clock;
    clock.start();
    while (clock.elapsed() < timeout_ms) {
        for (const auto& args : spy) {
            const auto o = args.at(0).value<RunOutcome>();
            if (!o.preview && pred(o.settings)) {  // a preview is not yet the run of those settings
                if (out) *out = o;
                return true;
            }
        }
        spy.clear();
        spy.wait(200);
    }
    return false;
}

QByteArray head(const QString& path, int n) {
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly)) return {};
    return f.read(n);
}

}  // namespace

class TstAppWindow : public QObject {
    Q_OBJECT
    MainWindow* w = nullptr;
    QByteArray layout_;  // the docks as first shown (viewTabsKeepTheirWholeTitles restores it)
private slots:
    void sessionArgumentIsTakenBeforeQtSeesIt() {
        // QGuiApplication swallows "--session ID" (X11 session management): the app's
        // --session FILE was silently ignored until it was taken out of argv first.
        QByteArray a0("stickslip"), a1("--preset"), a2("fig22"), a3("--session"), a4("/tmp/s.json"), a5("--raise"),
            a6("rig");
        char* argv[] = {a0.data(), a1.data(), a2.data(), a3.data(), a4.data(), a5.data(), a6.data(), nullptr};
        int argc = 7;
        QCOMPARE(takeSessionArgument(argc, argv), QStringLiteral("/tmp/s.json"));
        QCOMPARE(argc, 5);
        QCOMPARE(QByteArray(argv[2]), QByteArray("fig22"));
        QCOMPARE(QByteArray(argv[3]), QByteArray("--raise"));
        QCOMPARE(argv[5], nullptr);
        QByteArray b1("--session=/tmp/t.json"), b2("-session"), b3("/tmp/u.json");
        char* argv2[] = {a0.data(), b1.data(), nullptr};
        argc = 2;
        QCOMPARE(takeSessionArgument(argc, argv2), QStringLiteral("/tmp/t.json"));
        QCOMPARE(argc, 1);
        char* argv3[] = {a0.data(), b2.data(), b3.data(), a5.data(), a6.data(), nullptr};
        argc = 5;
        QCOMPARE(takeSessionArgument(argc, argv3), QStringLiteral("/tmp/u.json"));
        QCOMPARE(argc, 3);
        char* argv4[] = {a0.data(), a1.data(), a2.data(), nullptr};
        argc = 3;
        QCOMPARE(takeSessionArgument(argc, argv4), QString());
        QCOMPARE(argc, 3);
    }

    void initTestCase() {
        w = new MainWindow(/*restoreSettings=*/false);
        w->show();
        layout_ = w->saveState();
        QVERIFY(waitForRun(*w, [](const ModelSettings& s) { return s.preset == "fig20"; }));
        QVERIFY(w->statusText().contains("run "));
    }
    void cleanupTestCase() { delete w; }

    // The window fits a 1280×800 laptop screen in its default layout: every dock's minimum
    // together (the parameter panel beside the rig view and the plot tabs) is not wider or
    // taller than the screen, so no part of it opens off-screen (seen: 1465 px wide).
    void defaultLayoutFitsA1280x800Screen() {
        const QSize min = w->minimumSizeHint().expandedTo(w->minimumSize());
        QVERIFY2(min.width() <= 1280, qPrintable(QString("minimum width %1 px").arg(min.width())));
        QVERIFY2(min.height() <= 800, qPrintable(QString("minimum height %1 px").arg(min.height())));
        const QSize avail = w->screen()->availableGeometry().size();
        QVERIFY2(w->width() <= std::min(1280, std::max(avail.width(), min.width())) &&
                     w->height() <= std::min(800, std::max(avail.height(), min.height())),
                 qPrintable(QString("size %1 x %2 px on a %3 x %4 px screen").arg(w->width()).arg(w->height()).arg(avail.width()).arg(avail.height())));
    }

    // The plot views share one tabbed dock area: their tabs show whole titles and scroll,
    // also for a tab bar QMainWindow makes later (a view moved into another tab group).
    void viewTabsKeepTheirWholeTitles() {
        auto bars = [this] {
            QList<QTabBar*> shown;
            for (QTabBar* b : w->findChildren<QTabBar*>(QString(), Qt::FindDirectChildrenOnly))
                if (b->isVisible()) shown.append(b);
            return shown;
        };
        const int shown = static_cast<int>(bars().size());
        QVERIFY(shown > 0);
        bool poincare = false;
        for (QTabBar* b : bars()) {
            QCOMPARE(b->elideMode(), Qt::ElideNone);
            QVERIFY(b->usesScrollButtons());
            for (int i = 0; i < b->count(); ++i) poincare = poincare || b->tabText(i) == QStringLiteral("Poincaré section");
        }
        QVERIFY(poincare);
        w->tabifyDockWidget(w->dock("rig"), w->dock("timeseries"));
        QTRY_VERIFY(bars().size() > shown);
        for (QTabBar* b : bars()) QCOMPARE(b->elideMode(), Qt::ElideNone);
        w->restoreState(layout_);
        QTRY_COMPARE(static_cast<int>(bars().size()), shown);
    }

    void sliderChangeReachesThePlots() {
        // A closed view is not redrawn per result (checked below).
        w->dock("phase")->hide();
        const int poincareJobs = w->controller()->launchedCount(JobKind::Poincare);
        // A: 1 mm → 2.5 mm (position 250 of the 0–10 mm slider).
        w->panel()->slider("A")->setValue(250);
        RunOutcome o;
        QVERIFY(waitForRun(*w, [](const ModelSettings& s) { return std::abs(s.params.drive.amplitude_m - 2.5e-3) < 1e-12; }, &o));
        QCOMPARE(w->panel()->settings().params.drive.amplitude_m, o.settings.params.drive.amplitude_m);
        // The same run straight from the core.
        const RunResult direct = simulate(w->panel()->settings().paramsFor(LawKind::RateState));
        QVERIFY(direct.ok());
        QwtPlotCurve* x = w->views()->timeSeries()->curve("rate-state: slider x");
        QwtPlotCurve* u = w->views()->timeSeries()->curve("rate-state: stage u");
        QVERIFY(x && u);
        QCOMPARE(x->dataSize(), direct.samples.size());
        double maxU = 0;
        for (size_t i = 0; i < direct.samples.size(); i += 97) {
            QCOMPARE(x->sample(i).x(), direct.samples[i].t_s);
            QVERIFY(std::abs(x->sample(i).y() - 1e3 * direct.samples[i].slider_m) <= 1e-9);
        }
        for (size_t i = 0; i < u->dataSize(); ++i) maxU = std::max(maxU, std::abs(u->sample(i).y()));
        QVERIFY2(std::abs(maxU - 2.5) < 1e-3, qPrintable(QString::number(maxU)));   // the stage shows the new A in mm
        // The loop plot got the same run: its loop marks lie within the run's time span.
        const auto& marks = w->views()->frictionLoop()->loopMarks(LawKind::RateState);
        QVERIFY(!marks.empty());
        for (const auto& m : marks)
            QVERIFY(m.t0_s >= direct.samples.front().t_s && m.t1_s <= direct.samples.back().t_s && m.t0_s < m.t1_s);
        // Closed views are not redrawn per result: the phase portrait keeps the update and
        // shows this run once its dock is shown again.
        auto* phase = w->views()->phasePortrait();
        QVERIFY(!phase->isVisible());
        QVERIFY(phase->hasPendingUpdate());
        w->dock("phase")->show();
        QTRY_VERIFY(phase->isVisible());
        QVERIFY(!phase->hasPendingUpdate());
        QwtPlotCurve* traj = phase->curve("rate-state: trajectory");
        QVERIFY(traj);
        QCOMPARE(traj->dataSize(), direct.samples.size());
        for (size_t i = 0; i < direct.samples.size(); i += 97)
            QVERIFY(std::abs(traj->sample(i).x() - 1e3 * direct.samples[i].slider_m) <= 1e-9);
        // Tabified behind the loop view: the Poincaré view is visible but off screen, so it is not
        // redrawn per result; bringing its tab to the front draws this run's section, which
        // the run recorded (no Poincaré job) and which equals the core's poincareSection.
        QVERIFY(o.sectionInRun);
        QCOMPARE(w->controller()->launchedCount(JobKind::Poincare), poincareJobs);
        auto* poincare = w->views()->poincare();
        QVERIFY(poincare->isVisible());
        QVERIFY(!poincare->isOnScreen());
        QVERIFY(poincare->hasPendingUpdate());
        w->raiseView("poincare");
        QTRY_VERIFY(poincare->isOnScreen());
        QVERIFY(!poincare->hasPendingUpdate());
        PoincareOptions opt;
        opt.settleCycles = std::lround(o.settings.params.transientCycles);
        opt.cycles = std::lround(o.settings.params.cycles);
        const PoincareSection section = poincareSection(o.settings.paramsFor(LawKind::RateState), opt);
        QVERIFY(section.ok());
        QwtPlotCurve* dots = poincare->curve("rate-state: section");
        QVERIFY(dots);
        QCOMPARE(dots->dataSize(), section.size());
        for (size_t i = 0; i < section.size(); ++i) {
            QVERIFY(std::abs(dots->sample(i).x() - 1e3 * section.slider_m[i]) <= 1e-9);
            QVERIFY(std::abs(dots->sample(i).y() - section.relVel_mps[i]) <= 1e-9);
        }
        QVERIFY(!w->views()->frictionLoop()->isOnScreen());   // now behind the Poincaré tab
        w->raiseView("loop");
        QTRY_VERIFY(w->views()->frictionLoop()->isOnScreen());
        QVERIFY(!w->views()->frictionLoop()->hasPendingUpdate());
    }

    // Error-controlled stepping chosen in the Integration group: the worker's run is the core's
    // adaptive run of the same parameters (samples on the output grid, not on internal steps),
    // and the run records its Poincaré section from the dense output (no Poincaré job).
    void errorControlledSteppingEndToEnd() {
        QComboBox* box = w->panel()->steppingBox();
        const int i = box->findData(1e-4);
        QVERIFY(i > 0);
        const int poincareJobs = w->controller()->launchedCount(JobKind::Poincare);
        box->setCurrentIndex(i);
        emit box->activated(i);
        RunOutcome o;
        QVERIFY(waitForRun(*w, [](const ModelSettings& s) { return s.tolerance == 1e-4; }, &o));
        const SimParams p = o.settings.paramsFor(LawKind::RateState);
        QCOMPARE(p.integration.tolerance, 1e-4);
        const RunResult direct = simulate(p);
        QVERIFY(direct.ok());
        QCOMPARE(o.runs.front().run.samples.size(), direct.samples.size());
        const double spacing = p.integration.outputInterval_s;
        for (size_t k = 0; k < direct.samples.size(); k += 53) {
            QCOMPARE(o.runs.front().run.samples[k].slider_m, direct.samples[k].slider_m);
            QVERIFY(std::abs(direct.samples[k].t_s - (direct.samples.front().t_s + k * spacing)) < 1e-9);
        }
        QVERIFY(o.sectionInRun);
        QCOMPARE(w->controller()->launchedCount(JobKind::Poincare), poincareJobs);
        QVERIFY(!o.runs.front().section.slider_m.empty());
        // Back to the paper's fixed step for the tests below.
        box->setCurrentIndex(0);
        emit box->activated(0);
        QVERIFY(waitForRun(*w, [](const ModelSettings& s) { return s.tolerance == 0.0; }));
    }

    void presetSwitch() {
        w->panel()->loadPreset("fig16");   // prescribed slip, 5 cycles
        RunOutcome o;
        QVERIFY(waitForRun(*w, [](const ModelSettings& s) { return s.preset == "fig16"; }, &o));
        QVERIFY(o.settings.params.setup == SetupKind::Prescribed);
        QCOMPARE(o.runs.size(), size_t(1));
        QVERIFY(o.runs[0].run.ok());
        // Block with prescribed slip: the slider is held (x ≡ 0), the stage moves ±1 mm.
        QwtPlotCurve* x = w->views()->timeSeries()->curve("rate-state: slider x");
        QVERIFY(x);
        QCOMPARE(x->dataSize(), o.runs[0].run.samples.size());
        for (size_t i = 0; i < x->dataSize(); ++i) QCOMPARE(x->sample(i).y(), 0.0);
        // Both models overlaid: two sets of curves.
        w->panel()->modelBox()->setCurrentIndex(w->panel()->modelBox()->findData(int(ModelChoice::Both)));
        QVERIFY(waitForRun(*w, [](const ModelSettings& s) { return s.model == ModelChoice::Both; }, &o));
        QCOMPARE(o.runs.size(), size_t(2));
        QVERIFY(w->views()->timeSeries()->curve("Coulomb: F/t_N"));
        QVERIFY(w->views()->timeSeries()->curve("rate-state: F/t_N"));
        // Coulomb saturates at μ: |F/t_N| ≤ μ (+ nothing: rate independent).
        QwtPlotCurve* c = w->views()->timeSeries()->curve("Coulomb: F/t_N");
        double maxRatio = 0;
        for (size_t i = 0; i < c->dataSize(); ++i) maxRatio = std::max(maxRatio, std::abs(c->sample(i).y()));
        QVERIFY(std::abs(maxRatio - o.settings.params.lawParams<CoulombParams>().mu) < 1e-6);
        w->panel()->modelBox()->setCurrentIndex(w->panel()->modelBox()->findData(int(ModelChoice::RateState)));
        w->panel()->loadPreset("fig20");
        QVERIFY(waitForRun(*w, [](const ModelSettings& s) { return s.preset == "fig20" && s.model == ModelChoice::RateState; }));
        QVERIFY(!w->views()->timeSeries()->curve("Coulomb: F/t_N"));
    }

    void failureIsReportedInWords() {
        ModelSettings bad = w->panel()->settings();
        bad.params.rig.normalForce_N = -1.0;
        w->panel()->setSettings(bad);
        QVERIFY(waitForRun(*w, [](const ModelSettings& s) { return s.params.rig.normalForce_N < 0; }));
        QVERIFY2(w->statusText().contains("failed") && w->statusText().contains("tN = -1"), qPrintable(w->statusText()));
        w->panel()->loadPreset("fig20");
        QVERIFY(waitForRun(*w, [](const ModelSettings& s) { return s.params.rig.normalForce_N > 0; }));
        QVERIFY(!w->statusText().contains("failed"));
    }

    void exportEveryFormat() {
        QTemporaryDir dir;
        for (const auto& v : w->views()->views()) {
            if (!v.plot) continue;
            for (const char* ext : {"png", "svg", "pdf", "csv"}) {
                const QString path = dir.filePath(v.id + "." + ext);
                QString why;
                QVERIFY2(v.plot->exportTo(path, &why), qPrintable(v.id + ": " + why));
                const QByteArray h = head(path, 64);
                if (QByteArray(ext) == "png") QVERIFY(h.startsWith("\x89PNG\r\n\x1a\n"));
                if (QByteArray(ext) == "pdf") QVERIFY(h.startsWith("%PDF-"));
                if (QByteArray(ext) == "svg") QVERIFY(h.contains("<?xml") || h.contains("<svg"));
            }
        }
        // CSV values: the slider curve of the time series, in mm as displayed.
        const QString csv = dir.filePath("timeseries.csv");
        QFile f(csv);
        QVERIFY(f.open(QIODevice::ReadOnly));
        const QStringList lines = QString::fromUtf8(f.readAll()).split('\n');
        QwtPlotCurve* x = w->views()->timeSeries()->curve("rate-state: slider x");
        int checked = 0;
        size_t i = 0;
        for (const QString& line : lines) {
            if (!line.startsWith("rate-state: slider x,")) continue;
            const QStringList cells = line.split(',');
            QCOMPARE(cells.size(), 3);
            QVERIFY(std::abs(cells[1].toDouble() - x->sample(i).x()) <= 1e-12 * (1 + std::abs(x->sample(i).x())));
            QVERIFY(std::abs(cells[2].toDouble() - x->sample(i).y()) <= 1e-12 * (1 + std::abs(x->sample(i).y())));
            ++i;
            ++checked;
        }
        QCOMPARE(size_t(checked), x->dataSize());
        // Unknown format: an error, and nothing written.
        QString why;
        QVERIFY(!w->views()->timeSeries()->exportTo(dir.filePath("x.bmp"), &why));
        QVERIFY(!QFile::exists(dir.filePath("x.bmp")));
    }

    void measuredCsvOverlaidByColumnName() {
        QTemporaryDir dir;
        const QString path = dir.filePath("measured.csv");
        QFile f(path);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("# synthetic\ntime_s,stage_disp_m,friction_force_N\n0,0,0\n0.1,0.001,1.55\n0.2,0,-1.55\n");
        f.close();
        QString why;
        QVERIFY2(w->openMeasured(path, &why), qPrintable(why));
        QwtPlotCurve* u = w->views()->timeSeries()->curve("measured: stage_disp_m");
        QVERIFY(u);
        QCOMPARE(u->dataSize(), size_t(3));
        QCOMPARE(u->sample(1).y(), 1.0);   // mm on the displacement axis
        QwtPlotCurve* r = w->views()->timeSeries()->curve("measured: friction_force_N / t_N");
        QVERIFY(r);
        QVERIFY(std::abs(r->sample(1).y() - 1.55 / 6.2) < 1e-12);   // F / t_N with the panel's t_N
        // A bad file names file, line and column.
        const QString bad = dir.filePath("bad.csv");
        QFile b(bad);
        QVERIFY(b.open(QIODevice::WriteOnly));
        b.write("time_s,stage_disp_m\n0,0\n0.1,abc\n");
        b.close();
        QVERIFY(!w->openMeasured(bad, &why));
        QVERIFY2(why.contains("bad.csv") && why.contains(":3:"), qPrintable(why));
        QVERIFY(w->statusText().contains("bad.csv"));
        w->views()->clearMeasured();
        QVERIFY(!w->views()->timeSeries()->curve("measured: stage_disp_m"));
        QVERIFY(w->views()->timeSeries()->curve("rate-state: slider x"));
        // Drag and drop of the same file onto the window overlays it too.
        QMimeData mime;
        mime.setUrls({QUrl::fromLocalFile(path)});
        QDropEvent drop(QPointF(200, 200), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
        // Delivered straight to the window's handler (QApplication::notify only forwards a
        // drop after a real drag entered the widget).
        static_cast<QObject*>(w)->event(&drop);
        QVERIFY(drop.isAccepted());
        QVERIFY(w->views()->timeSeries()->curve("measured: stage_disp_m"));
        w->views()->clearMeasured();
    }

    // Several measured files dropped on the window are runs of one dataset: they open the
    // Identify panel's import with all of them (not an overlay of each in turn).
    void severalDroppedFilesGoToTheImport() {
        QTemporaryDir dir;
        QStringList paths;
        for (const char* name : {"run_01.csv", "run_02.csv"}) {
            paths << dir.filePath(name);
            QFile f(paths.back());
            QVERIFY(f.open(QIODevice::WriteOnly));
            f.write("time_s,stage_disp_m,friction_force_N\n0,0,0\n0.1,0.001,1.55\n0.2,0,-1.55\n");
        }
        w->views()->clearMeasured();
        w->dock("identify")->hide();
        QStringList shown;
        bool wasModal = false;
        // The import dialog is modal: read it and close it from inside its own event loop.
        QTimer poll;
        poll.setInterval(20);
        connect(&poll, &QTimer::timeout, [&] {
            if (auto* d = qobject_cast<ImportDialog*>(QApplication::activeModalWidget())) {
                shown = d->files();
                wasModal = true;
                d->reject();
            }
        });
        poll.start();
        QMimeData mime;
        mime.setUrls({QUrl::fromLocalFile(paths[0]), QUrl::fromLocalFile(paths[1])});
        QDropEvent drop(QPointF(200, 200), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
        static_cast<QObject*>(w)->event(&drop);
        QVERIFY(drop.isAccepted());
        QTRY_VERIFY_WITH_TIMEOUT(wasModal, 20000);
        poll.stop();
        QCOMPARE(shown, paths);
        QVERIFY(w->dock("identify")->isVisible());
        // Nothing was overlaid on the plots.
        QVERIFY(!w->views()->timeSeries()->curve("measured: stage_disp_m"));
    }

    void sessionSaveAndLoad() {
        QTemporaryDir dir;
        const QString path = dir.filePath("session.json");
        w->panel()->spinBox("eta")->setValue(0.45);
        w->panel()->modelBox()->setCurrentIndex(w->panel()->modelBox()->findData(int(ModelChoice::Both)));
        w->dock("spectrum")->hide();
        const ModelSettings saved = w->panel()->settings();
        QString why;
        QVERIFY2(w->saveSessionTo(path, &why), qPrintable(why));
        w->panel()->loadPreset("fig23");
        w->panel()->modelBox()->setCurrentIndex(w->panel()->modelBox()->findData(int(ModelChoice::Coulomb)));
        w->dock("spectrum")->show();
        QVERIFY2(w->loadSessionFrom(path, &why), qPrintable(why));
        const ModelSettings back = w->panel()->settings();
        for (const auto& k : paramKeys()) {
            double a = 0, b = 0;
            getParam(saved.params, k, a);
            getParam(back.params, k, b);
            QVERIFY2(a == b, k.c_str());
        }
        QCOMPARE(back.params.lawParams<RateStateParams>().eta_s_per_m, 0.45);
        QVERIFY(back.model == ModelChoice::Both);
        QVERIFY(w->dock("spectrum")->isHidden());
        QVERIFY(!w->dock("timeseries")->isHidden());
        // And the views follow the loaded parameters.
        QVERIFY(waitForRun(*w, [](const ModelSettings& s) {
            return s.params.lawParams<RateStateParams>().eta_s_per_m == 0.45 && s.model == ModelChoice::Both;
        }));
    }
};

QTEST_MAIN(TstAppWindow)
#include "tst_app_window.moc"
