// stickslip: the desktop explorer. Options: --preset NAME (default fig20), --raise VIEW
// (bring a view's dock to the front, e.g. rig), --analysis sweep|map (start the Analysis
// menu's sweep or map with its dialog's values), --screenshot FILE.png (grab the window once
// the first results, or the analysis, are drawn, then quit); an optional FILE argument opens
// a session (.json) or overlays a measured run (CSV), as the desktop entry passes it.
#include <QApplication>
#include <QCursor>
#include <QIcon>
#include <QCommandLineParser>
#include <QDockWidget>
#include <QScreen>
#include <QTimer>
#include <cstdio>
#include <memory>

#include "core/heap_settings.hpp"
#include "core/presets.hpp"
#include "core/version.hpp"
#include "command_line.hpp"
#include "main_window.hpp"
#include "parameter_panel.hpp"
#include "simulation_controller.hpp"
#include "sweep_dialogs.hpp"
#include "view_set.hpp"
#include "widgets/rig_view.hpp"

namespace {

void setUpApplication() {
    QApplication::setOrganizationName("StickSlipLab");
    QApplication::setApplicationName("stickslip");
    QApplication::setApplicationVersion(stickslip::kVersion);
    QApplication::setDesktopFileName("stickslip");
    QIcon icon;
    for (int px : {16, 32, 48, 64, 128, 256}) icon.addFile(QString(":/icons/stickslip-%1.png").arg(px));
    QApplication::setWindowIcon(icon);
}

struct Options {
    QString preset, screenshotFile, raise, screenshotView, analysis;
    bool screenshot = false, raiseSet = false, viewSet = false;
    QStringList files;
};

// The command line (header comment). False (exitCode set) when it names an unknown analysis.
bool parseOptions(const QApplication& app, Options& o, int& exitCode) {
    QCommandLineParser cli;
    cli.setApplicationDescription("StickSlip Lab: explorer for friction-induced stick-slip vibration");
    cli.addHelpOption();
    cli.addVersionOption();
    QCommandLineOption presetOpt("preset", "Built-in parameter set to start with (default fig20).", "NAME", "fig20");
    QCommandLineOption shotOpt("screenshot", "Grab the window after the first results, save PNG, quit.", "FILE");
    QCommandLineOption raiseOpt("raise", "Bring this view to the front (timeseries, rig, loop, phase, poincare, "
                                         "spectrum, autocorrelation, bifurcation, map).", "VIEW");
    QCommandLineOption shotViewOpt("screenshot-view",
                                   "With --screenshot: grab only this view (floated at 960x560), e.g. rig.", "VIEW");
    QCommandLineOption analysisOpt("analysis",
                                   "Start this analysis with its dialog's values: sweep (bifurcation) or map "
                                   "(periodicity map); with --screenshot, grab when it is drawn.",
                                   "KIND");
    // Listed for --help only: takeSessionArgument has already taken it out of argv.
    QCommandLineOption sessionOpt("session", "Open this session file.", "FILE");
    cli.addOptions({presetOpt, shotOpt, raiseOpt, sessionOpt, shotViewOpt, analysisOpt});
    cli.addPositionalArgument("file", "Session (.json) to open or measured run (CSV) to overlay.", "[FILE]");
    cli.process(app);
    o.analysis = cli.value(analysisOpt);
    if (cli.isSet(analysisOpt) && o.analysis != "sweep" && o.analysis != "map") {
        std::fprintf(stderr, "stickslip: --analysis '%s' is not one of: sweep, map\n", qPrintable(o.analysis));
        exitCode = 2;
        return false;
    }
    o.preset = cli.value(presetOpt);
    o.screenshot = cli.isSet(shotOpt);
    o.screenshotFile = cli.value(shotOpt);
    o.raiseSet = cli.isSet(raiseOpt);
    o.raise = cli.value(raiseOpt);
    o.viewSet = cli.isSet(shotViewOpt);
    o.screenshotView = cli.value(shotViewOpt);
    o.files = cli.positionalArguments();
    return true;
}

// The preset, then the session and the files to open. False (exitCode set) on the first that fails.
bool openInputs(stickslip::gui::MainWindow& w, const Options& o, const QString& sessionFile, int& exitCode) {
    if (!w.panel()->loadPreset(o.preset)) {
        std::fprintf(stderr, "stickslip: unknown preset '%s'\n", qPrintable(o.preset));
        exitCode = 2;
        return false;
    }
    if (!sessionFile.isEmpty()) {
        QString why;
        if (!w.loadSessionFrom(sessionFile, &why)) {
            std::fprintf(stderr, "stickslip: %s\n", qPrintable(why));
            exitCode = 3;
            return false;
        }
    }
    for (const QString& file : o.files) {
        QString why;
        if (!w.openFile(file, &why)) {
            std::fprintf(stderr, "stickslip: %s\n", qPrintable(why));
            exitCode = 3;
            return false;
        }
    }
    return true;
}

// --screenshot: after the first outcome with the final parameters (the refined run, or the
// analysis asked for), let the plots and the rig animation draw for a moment, grab `target`,
// save it and quit with 0, or 1 if it could not be saved.
void armScreenshot(stickslip::gui::MainWindow& w, QWidget* target, const QString& file, const QString& analysis) {
    // Park the pointer in the screen's corner, so no plot shows its cursor read-out.
    if (const QScreen* screen = QGuiApplication::primaryScreen()) QCursor::setPos(screen->geometry().bottomRight());
    auto armed = std::make_shared<bool>(true);
    auto grabLater = [&w, target, file, armed] {
        if (!*armed) return;
        *armed = false;
        // Animate the rig so the picture shows it (and the time-series cursor) mid-run.
        w.views()->rig()->play();
        QTimer::singleShot(2500, &w, [&w, target, file] {
            w.views()->rig()->pause();
            const QPixmap shot = target->grab();
            const bool ok = shot.save(file, "PNG");
            std::fprintf(stderr, "stickslip: %s %s (%dx%d)\n", ok ? "saved" : "could not save", qPrintable(file),
                         shot.width(), shot.height());
            QApplication::exit(ok ? 0 : 1);
        });
    };
    auto* ctl = w.controller();
    if (analysis == "sweep")
        QObject::connect(ctl, &stickslip::gui::SimulationController::sweepFinished, &w, grabLater);
    else if (analysis == "map")
        QObject::connect(ctl, &stickslip::gui::SimulationController::mapFinished, &w, grabLater);
    else
        QObject::connect(&w, &stickslip::gui::MainWindow::runShown, &w, [grabLater](const stickslip::gui::RunOutcome& o) {
            if (!o.preview) grabLater();  // the refined run, not its first frame
        });
}

}  // namespace

int main(int argc, char** argv) {
    stickslip::applyHeapSettings();  // before any thread starts (heap_settings.hpp)
    const QString sessionFile = stickslip::gui::takeSessionArgument(argc, argv);
    QApplication app(argc, argv);
    setUpApplication();
    Options o;
    int exitCode = 0;
    if (!parseOptions(app, o, exitCode)) return exitCode;
    stickslip::gui::MainWindow w(/*restoreSettings=*/!o.screenshot);
    if (!openInputs(w, o, sessionFile, exitCode)) return exitCode;
    if (o.raiseSet) w.raiseView(o.raise);
    QWidget* target = &w;
    if (o.screenshot && o.viewSet) {
        QDockWidget* d = w.dock(o.screenshotView);
        if (!d) {
            std::fprintf(stderr, "stickslip: unknown view '%s'\n", qPrintable(o.screenshotView));
            return 2;
        }
        d->setFloating(true);
        d->move(0, 0);  // away from the parked pointer (bottom-right), so no cursor read-out shows
        d->resize(960, 560);
        target = d;
    }
    w.show();
    if (o.screenshot) armScreenshot(w, target, o.screenshotFile, o.analysis);
    if (o.analysis == "sweep") w.sweepDialog()->start();
    if (o.analysis == "map") w.mapDialog()->start();
    return app.exec();
}
