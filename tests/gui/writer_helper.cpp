// Helper of tst_crash_safe_files: calls the app's own writers (saveSession, PlotWidget::exportTo)
// over and over, so that the test can SIGKILL it at any moment of a write.
//   writer_helper KIND DIR     KIND: session, png, svg, pdf, csv
// Writes DIR/a.KIND and DIR/b.KIND (the two valid versions), then DIR/target.KIND = a, each only
// when it is not there yet, prints "ready" on stdout and then rewrites DIR/target.KIND
// alternately as the other version and back until killed.
#include <QApplication>
#include <QDir>
#include <QFile>
#include <QTextStream>
#include <cmath>
#include <cstdio>

#include "core/presets.hpp"
#include "widgets/series_plot.hpp"
#include "session.hpp"
#include "tests/file_bytes.hpp"

using namespace stickslip;

namespace {

gui::Session sessionVersion(int which) {
    gui::Session s;
    Preset p;
    findPreset("fig20", p);
    s.settings.params = p.params;
    s.settings.params.drive.amplitude_m = which == 0 ? 1e-3 : 2e-3;
    s.settings.preset = "fig20";
    s.visibleViews = QStringList{"timeseries", which == 0 ? "rig" : "phase"};
    return s;
}

// Large and dense enough that rendering and encoding take a noticeable time.
void fillPlot(widgets::SeriesPlot& plot, int which) {
    widgets::PlotSeries s;
    s.label = which == 0 ? "a" : "b";
    for (int i = 0; i < 200000; ++i) {
        const double x = i * 1e-4;
        s.x.push_back(x);
        s.y.push_back(std::sin((which + 1) * 7.0 * x) + 0.3 * std::sin(313.0 * x));
    }
    plot.setTitles(which == 0 ? "version a" : "version b", "t [s]", "y");
    plot.setSeries({s});
}

}  // namespace

int main(int argc, char** argv) {
    QApplication app(argc, argv);
    if (argc != 3) {
        std::fprintf(stderr, "usage: writer_helper session|png|svg|pdf|csv DIR\n");
        return 2;
    }
    const QString kind = QString::fromLocal8Bit(argv[1]);
    const QDir dir(QString::fromLocal8Bit(argv[2]));
    widgets::SeriesPlot plots[2];
    for (int w = 0; w < 2; ++w) {
        plots[w].resize(800, 600);
        fillPlot(plots[w], w);
    }
    auto write = [&](int which, const QString& path) {
        QString why;
        const bool ok = kind == "session" ? gui::saveSession(sessionVersion(which), path, &why)
                                          : plots[which].exportTo(path, &why);
        if (!ok) std::fprintf(stderr, "writer_helper: %s\n", qPrintable(why));
        return ok;
    };
    // The test starts this helper once per kill in the same DIR: the versions and the target
    // left by the last one (a complete version, or the test has already failed) are kept, so
    // that a start costs no writes of its own (three renderings of 200 000 points each, seconds
    // under the sanitizers).
    const QString target = dir.filePath("target." + kind);
    auto writeOnce = [&](int which, const QString& path) { return QFile::exists(path) || write(which, path); };
    if (!writeOnce(0, dir.filePath("a." + kind)) || !writeOnce(1, dir.filePath("b." + kind)) || !writeOnce(0, target))
        return 1;
    // The first rewrite is the version the target does not hold, so that a kill can catch the
    // change itself.
    const bool holdsB = sameExportVersion(kind, readAll(target), readAll(dir.filePath("b." + kind)));
    std::printf("ready\n");
    std::fflush(stdout);
    for (int i = holdsB ? 0 : 1;; ++i)
        if (!write(i % 2, target)) return 1;
}
