// stickslip: the desktop explorer. Options: --preset NAME (default fig20), --raise VIEW
// (bring a view's dock to the front, e.g. rig), --screenshot FILE.png (grab the window once
// the first results are drawn, then quit).
#include <QApplication>
#include <QCommandLineParser>
#include <QDockWidget>
#include <QScreen>
#include <QTimer>
#include <cstdio>
#include <memory>

#include "core/presets.hpp"
#include "core/version.hpp"
#include "main_window.hpp"
#include "parameter_panel.hpp"
#include "view_set.hpp"
#include "widgets/rig_view.hpp"

int main(int argc, char** argv) {
    QApplication app(argc, argv);
    QApplication::setOrganizationName("StickSlipLab");
    QApplication::setApplicationName("stickslip");
    QApplication::setApplicationVersion(stickslip::kVersion);

    QCommandLineParser cli;
    cli.setApplicationDescription("StickSlip Lab: explorer for friction-induced stick-slip vibration");
    cli.addHelpOption();
    cli.addVersionOption();
    QCommandLineOption presetOpt("preset", "Built-in parameter set to start with (default fig20).", "NAME", "fig20");
    QCommandLineOption shotOpt("screenshot", "Grab the window after the first results, save PNG, quit.", "FILE");
    QCommandLineOption raiseOpt("raise", "Bring this view to the front (timeseries, rig, loop, phase, poincare, "
                                         "spectrum, autocorrelation, bifurcation, map).", "VIEW");
    QCommandLineOption sessionOpt("session", "Open this session file.", "FILE");
    QCommandLineOption shotViewOpt("screenshot-view",
                                   "With --screenshot: grab only this view (floated at 960x560), e.g. rig.", "VIEW");
    cli.addOptions({presetOpt, shotOpt, raiseOpt, sessionOpt, shotViewOpt});
    cli.process(app);

    const bool screenshot = cli.isSet(shotOpt);
    stickslip::gui::MainWindow w(/*restoreSettings=*/!screenshot);
    const QString preset = cli.value(presetOpt);
    if (!w.panel()->loadPreset(preset)) {
        std::fprintf(stderr, "stickslip: unknown preset '%s'\n", qPrintable(preset));
        return 2;
    }
    if (cli.isSet(sessionOpt)) {
        QString why;
        if (!w.loadSessionFrom(cli.value(sessionOpt), &why)) {
            std::fprintf(stderr, "stickslip: %s\n", qPrintable(why));
            return 3;
        }
    }
    if (cli.isSet(raiseOpt)) w.raiseView(cli.value(raiseOpt));
    QWidget* target = &w;
    if (screenshot && cli.isSet(shotViewOpt)) {
        QDockWidget* d = w.dock(cli.value(shotViewOpt));
        if (!d) {
            std::fprintf(stderr, "stickslip: unknown view '%s'\n", qPrintable(cli.value(shotViewOpt)));
            return 2;
        }
        d->setFloating(true);
        d->resize(960, 560);
        target = d;
    }
    w.show();

    if (screenshot) {
        const QString file = cli.value(shotOpt);
        // After the first outcome with the final parameters: let the plots (and the rig
        // animation) draw for a moment, then grab the window itself.
        auto armed = std::make_shared<bool>(true);
        QObject::connect(&w, &stickslip::gui::MainWindow::runShown, &w, [&w, target, file, armed](const auto&) {
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
        });
    }
    return app.exec();
}
