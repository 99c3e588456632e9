// The import dialog (issue 5): the default mapping picks the core's column names in a
// synthetic dynamics run and a friction-damper run; a changed mapping and units reach
// datasetOptions() and the loaded dataset exactly as io::loadDataset reads them; bad files
// and bad mappings are named with file:line:column, keep OK disabled and load nothing; the
// raw-versus-cleaned plot shows exactly what preprocessRun produces.
#include <QDir>
#include <QFile>
#include <QFontMetrics>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QSignalSpy>
#include <QTabWidget>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <qwt_plot_curve.h>
#include <sstream>

#include "core/identify/preprocess.hpp"
#include "core/io/csv_table.hpp"
#include "core/io/dataset.hpp"
#include "import_dialog.hpp"
#include "widgets/signal_compare_plot.hpp"

using namespace stickslip;
using namespace stickslip::gui;
using io::Signal;

namespace {

const QString kShared = QStringLiteral(STICKSLIP_SHARED_DIR);
QString syntheticRun() { return kShared + "/data/synthetic/D05/run_01.csv"; }
QString damperRun() { return kShared + "/data/real/friction-damper/1Hz_30lb_1in.csv"; }

bool waitIdle(ImportDialog& d, int ms = 60000) {
    QElapsedTimer t;
    t.start();
    while (t.elapsed() < ms) {
        QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
        QTest::qWait(10);
        if (!d.isBusy()) return true;
    }
    return false;
}

// Every channel and setting of two datasets equal (bit for bit).
void compareDatasets(const io::Dataset& a, const io::Dataset& b) {
    QCOMPARE(a.runs.size(), b.runs.size());
    QCOMPARE(a.manifestPath, b.manifestPath);
    for (size_t r = 0; r < a.runs.size(); ++r) {
        QCOMPARE(a.runs[r].file, b.runs[r].file);
        for (size_t k = 0; k < io::kSignalCount; ++k) QVERIFY(a.runs[r].channels[k] == b.runs[r].channels[k]);
        QVERIFY(a.runs[r].settings == b.runs[r].settings);
        QVERIFY(a.runs[r].sourceColumn == b.runs[r].sourceColumn);
    }
}

std::vector<std::string> toStd(const QStringList& l) {
    std::vector<std::string> out;
    for (const QString& s : l) out.push_back(s.toStdString());
    return out;
}

void writeText(const QString& path, const std::string& text) {
    std::ofstream out(path.toStdString());
    out << text;
}

std::vector<QPointF> samplesOf(const QwtPlotCurve* c) {
    std::vector<QPointF> out;
    for (size_t i = 0; i < c->dataSize(); ++i) out.push_back(c->sample(static_cast<int>(i)));
    return out;
}

}  // namespace

class TstImportDialog : public QObject {
    Q_OBJECT
private slots:
    void defaultMappingSyntheticRun() {
        ImportDialog d({syntheticRun()});
        QVERIFY(waitIdle(d));
        QCOMPARE(d.column(Signal::Time), QStringLiteral("time_s"));
        QCOMPARE(d.column(Signal::StageDisp), QStringLiteral("stage_disp_m"));
        QCOMPARE(d.column(Signal::SliderDisp), QStringLiteral("slider_disp_m"));
        QCOMPARE(d.column(Signal::Friction), QStringLiteral("friction_force_N"));
        QCOMPARE(d.column(Signal::Normal), QStringLiteral("normal_force_N"));
        QCOMPARE(d.column(Signal::SliderAccel), QStringLiteral("slider_accel_mps2"));
        for (Signal s : {Signal::Slip, Signal::RelVel, Signal::StageVel, Signal::SliderVel, Signal::Tension})
            QVERIFY2(d.column(s).isEmpty(), io::signalKey(s));
        QVERIFY(d.setup() == SetupKind::Dynamics);   // slider displacement present, as the CLI decides
        QVERIFY(d.datasetOptions().mapping.columns.empty());
        QVERIFY(d.datasetOptions().mapping.scaleToSI.empty());
        QVERIFY(QString::fromStdString(d.datasetOptions().manifestPath).endsWith("D05/manifest.json"));
        QVERIFY2(d.isValid(), qPrintable(d.errorText()));
        QVERIFY(d.okButton()->isEnabled());

        // The preview shows the first 50 rows as the core CSV reader reads them.
        io::CsvTable table;
        io::CsvError cerr;
        QVERIFY(io::readCsvTable(syntheticRun().toStdString(), table, cerr));
        QTableWidget* t = d.previewTable();
        QCOMPARE(t->columnCount(), static_cast<int>(table.header.size()));
        QCOMPARE(t->rowCount(), 50);
        QVERIFY(t->horizontalHeaderItem(3)->text().startsWith("friction_force_N"));
        QVERIFY(t->horizontalHeaderItem(3)->text().contains(QStringLiteral("\u2192 F")));
        QCOMPARE(t->item(49, 1)->text().toDouble(), table.columns[1][49]);
        // Every header fits its column in bold (the style paints mapped headers bold).
        QFont bold = t->horizontalHeader()->font();
        bold.setBold(true);
        const QFontMetrics fm(bold);
        for (int j = 0; j < t->columnCount(); ++j)
            for (const QString& line : t->horizontalHeaderItem(j)->text().split('\n'))
                QVERIFY2(t->columnWidth(j) > fm.horizontalAdvance(line),
                         qPrintable(line + ": " + QString::number(t->columnWidth(j)) + " px"));

        // OK loads exactly what io::loadDataset loads with the dialog's options.
        d.accept();
        QTRY_COMPARE_WITH_TIMEOUT(d.result(), static_cast<int>(QDialog::Accepted), 30000);
        io::Dataset direct;
        io::DatasetError err;
        QVERIFY(io::loadDataset(toStd(d.files()), d.datasetOptions(), direct, err));
        compareDatasets(d.dataset(), direct);
        QCOMPARE(d.dataset().runs.front().settingSource.at("k"), std::string("manifest"));
    }

    void defaultMappingDamperRun() {
        ImportDialog d({damperRun()});
        QVERIFY(waitIdle(d));
        QCOMPARE(d.column(Signal::Time), QStringLiteral("time_s"));
        QCOMPARE(d.column(Signal::StageDisp), QStringLiteral("stage_disp_m"));
        QCOMPARE(d.column(Signal::StageVel), QStringLiteral("stage_vel_mps"));
        QCOMPARE(d.column(Signal::Friction), QStringLiteral("friction_force_N"));
        QCOMPARE(d.column(Signal::Tension), QStringLiteral("band_tension_N"));
        for (Signal s : {Signal::SliderDisp, Signal::Normal, Signal::Slip, Signal::SliderAccel})
            QVERIFY2(d.column(s).isEmpty(), io::signalKey(s));
        QVERIFY(d.setup() == SetupKind::Prescribed);  // no slider displacement
        QVERIFY(d.datasetOptions().manifestPath.empty());
        QVERIFY2(d.isValid(), qPrintable(d.errorText()));

        // Units: the damper's force read as lbf, and its stage as mm (both deliberately wrong
        // here, to see the conversion): values are the file's times the factors.
        d.setUnit(Signal::Friction, "lbf");
        d.setUnit(Signal::StageDisp, "mm");
        QVERIFY(waitIdle(d));
        QVERIFY2(d.isValid(), qPrintable(d.errorText()));
        const io::DatasetOptions o = d.datasetOptions();
        QCOMPARE(o.mapping.scaleToSI.size(), size_t(2));
        QCOMPARE(o.mapping.scaleToSI.at(Signal::StageDisp), 1e-3);
        QVERIFY(std::abs(o.mapping.scaleToSI.at(Signal::Friction) - 4.4482216152605) < 1e-9);
        d.accept();
        QTRY_COMPARE_WITH_TIMEOUT(d.result(), static_cast<int>(QDialog::Accepted), 30000);
        io::Dataset direct;
        io::DatasetError err;
        QVERIFY(io::loadDataset(toStd(d.files()), o, direct, err));
        compareDatasets(d.dataset(), direct);
        io::CsvTable table;
        io::CsvError cerr;
        QVERIFY(io::readCsvTable(damperRun().toStdString(), table, cerr));
        const io::Run& r = d.dataset().runs.front();
        QCOMPARE(r[Signal::Friction].size(), table.rows());
        for (size_t i = 0; i < table.rows(); i += 997) {
            QCOMPARE(r[Signal::Friction][i], table.columns[3][i] * o.mapping.scaleToSI.at(Signal::Friction));
            QCOMPARE(r[Signal::StageDisp][i], table.columns[1][i] * 1e-3);
        }
        QCOMPARE(r.settingSource.at("tN"), std::string("column band_tension_N (mean; reference load)"));
    }

    void renamedColumnsWithUnits() {
        // A synthetic run rewritten with other names and units (time in ms, displacements in mm,
        // forces in kN): mapped by hand it must give the original SI values.
        QTemporaryDir dir;
        QVERIFY(dir.isValid());
        io::CsvTable src;
        io::CsvError cerr;
        QVERIFY(io::readCsvTable(syntheticRun().toStdString(), src, cerr));
        std::ostringstream text;
        text << std::setprecision(17) << "# rewritten\nt_ms;u_mm;x_mm;Fx_kN;Fn\n";
        const size_t n = 3000;
        for (size_t i = 0; i < n; ++i)
            text << src.columns[0][i] * 1e3 << ';' << src.columns[1][i] * 1e3 << ';' << src.columns[2][i] * 1e3 << ';'
                 << src.columns[3][i] * 1e-3 << ';' << src.columns[4][i] << '\n';
        const QString path = dir.filePath("renamed.csv");
        writeText(path, text.str());

        ImportDialog d({path});
        QVERIFY(waitIdle(d));
        QVERIFY(d.column(Signal::Time).isEmpty());
        QVERIFY(!d.isValid());
        QVERIFY(!d.okButton()->isEnabled());
        QVERIFY(d.errorText().contains("time column is required"));

        d.setColumn(Signal::Time, "t_ms");
        d.setUnit(Signal::Time, "ms");
        d.setColumn(Signal::StageDisp, "u_mm");
        d.setUnit(Signal::StageDisp, "mm");
        d.setColumn(Signal::SliderDisp, "x_mm");
        d.setUnit(Signal::SliderDisp, "mm");
        d.setColumn(Signal::Friction, "Fx_kN");
        d.setUnit(Signal::Friction, "kN");
        d.setColumn(Signal::Normal, "Fn");
        QVERIFY(waitIdle(d));
        QVERIFY2(d.isValid(), qPrintable(d.errorText()));
        QVERIFY(d.setup() == SetupKind::Dynamics);
        const io::DatasetOptions o = d.datasetOptions();
        const std::map<Signal, std::string> cols{{Signal::Time, "t_ms"}, {Signal::StageDisp, "u_mm"},
                                                 {Signal::SliderDisp, "x_mm"}, {Signal::Friction, "Fx_kN"},
                                                 {Signal::Normal, "Fn"}};
        QVERIFY(o.mapping.columns == cols);
        const std::map<Signal, std::string> units{{Signal::Time, "ms"}, {Signal::StageDisp, "mm"},
                                                  {Signal::SliderDisp, "mm"}, {Signal::Friction, "kN"}};
        QVERIFY(o.mapping.unitText == units);
        d.accept();
        QTRY_COMPARE_WITH_TIMEOUT(d.result(), static_cast<int>(QDialog::Accepted), 30000);
        io::Dataset direct;
        io::DatasetError err;
        QVERIFY(io::loadDataset(toStd(d.files()), o, direct, err));
        compareDatasets(d.dataset(), direct);
        const io::Run& r = d.dataset().runs.front();
        QCOMPARE(r.size(), n);
        for (size_t i = 0; i < n; ++i) {
            QVERIFY(std::abs(r[Signal::Time][i] - src.columns[0][i]) <= 1e-14 * (1 + src.columns[0][i]));
            QVERIFY(std::abs(r[Signal::StageDisp][i] - src.columns[1][i]) <= 1e-15);
            QVERIFY(std::abs(r[Signal::Friction][i] - src.columns[3][i]) <= 1e-12 * (1 + std::abs(src.columns[3][i])));
        }
    }

    void unusedSignalIsDroppedAndTnFromManifest() {
        // "(none)" for the normal force although the file has it: not in the dataset, and t_N
        // comes from the manifest instead of the column mean.
        ImportDialog d({syntheticRun()});
        QVERIFY(waitIdle(d));
        d.setColumn(Signal::Normal, QString());
        QVERIFY(waitIdle(d));
        QVERIFY(d.unmappedSignals() == std::vector<Signal>{Signal::Normal});
        d.accept();
        QTRY_COMPARE_WITH_TIMEOUT(d.result(), static_cast<int>(QDialog::Accepted), 30000);
        const io::Run& r = d.dataset().runs.front();
        QVERIFY(!r.has(Signal::Normal));
        QVERIFY(r.has(Signal::Friction));
        io::Manifest man;
        io::DatasetError err;
        QVERIFY(io::readManifest(d.datasetOptions().manifestPath, man, err));
        QCOMPARE(r.settings.at("tN"), man.runs.at("run_01.csv").at("tN"));
        QCOMPARE(r.settingSource.at("tN"), std::string("manifest"));
        // The options alone say the same to the core loader (as --columns normal=- would).
        QCOMPARE(d.datasetOptions().mapping.columns.at(Signal::Normal), std::string(io::kNotMapped));
        io::Dataset direct;
        QVERIFY2(io::loadDataset({syntheticRun().toStdString()}, d.datasetOptions(), direct, err), err.what().c_str());
        QVERIFY(!direct.runs.front().has(Signal::Normal));
        QCOMPARE(direct.runs.front().settings.at("tN"), r.settings.at("tN"));
    }

    void malformedCsvIsNamedAndNothingLoads() {
        QTemporaryDir dir;
        const QString path = dir.filePath("bad.csv");
        writeText(path, "time_s,stage_disp_m,friction_force_N\n0.000,1e-4,0.5\n0.001,2e-4,0.6\n0.002,3e-4x,0.7\n");
        io::CsvTable table;
        io::CsvError cerr;
        QVERIFY(!io::readCsvTable(path.toStdString(), table, cerr));
        QCOMPARE(cerr.line, 4L);   // the file as written: line 4, second column
        QVERIFY(cerr.column > 0);

        ImportDialog d({syntheticRun(), path});
        QVERIFY(waitIdle(d));
        QVERIFY(!d.isValid());
        QVERIFY(!d.okButton()->isEnabled());
        const QString where = QStringLiteral("%1:4:%2:").arg(path).arg(cerr.column);
        QVERIFY2(d.errorText().startsWith(where), qPrintable(d.errorText()));
        QVERIFY(d.messageLabel()->text().contains(where));
        d.accept();   // refused: nothing is loaded, the dialog stays open
        QVERIFY(waitIdle(d));
        QVERIFY(d.result() != QDialog::Accepted);
        QVERIFY(d.dataset().runs.empty());

        // Removing the bad file makes it valid again.
        d.setFiles({syntheticRun()});
        QVERIFY(waitIdle(d));
        QVERIFY2(d.isValid(), qPrintable(d.errorText()));
    }

    // A value beyond the physical ranges (core/io/channel_ranges.hpp) is refused by the core
    // reader the dialog loads through: nothing loads and the dialog shows the core's message.
    void outOfRangeValueRefusedWithTheCoreMessage() {
        QTemporaryDir dir;
        const QString path = dir.filePath("huge.csv");
        std::string text = "time_s,stage_disp_m,friction_force_N\n";
        for (int i = 0; i < 10; ++i) text += std::to_string(i * 0.001) + ",1e-4," + (i == 6 ? "5e6" : "0.5") + "\n";
        writeText(path, text);
        io::Run run;
        io::DatasetError err;
        QVERIFY(!io::loadRun(path.toStdString(), io::ColumnMapping{}, run, err));
        QVERIFY2(err.what().find("allowed range") != std::string::npos, err.what().c_str());

        ImportDialog d({path});
        QVERIFY(waitIdle(d));
        if (d.isValid()) {  // the dialog's own checks pass; loading refuses the file
            QSignalSpy failed(&d, &ImportDialog::loadFailed);
            d.accept();
            QTRY_COMPARE_WITH_TIMEOUT(failed.count(), 1, 30000);
        }
        QVERIFY(d.result() != QDialog::Accepted);
        QVERIFY(d.dataset().runs.empty());
        QCOMPARE(d.errorText(), QString::fromStdString(err.what()));
    }

    void unknownColumnAndBadTimeWordedAsTheCore() {
        QTemporaryDir dir;
        const QString path = dir.filePath("backwards.csv");
        writeText(path, "# rig 2\ntime_s,stage_disp_m,friction_force_N\n"
                        "0.000,1e-4,0.5\n0.001,2e-4,0.6\n0.002,3e-4,0.7\n0.003,3e-4,0.7\n"
                        "0.002,3e-4,0.7\n0.005,3e-4,0.7\n0.006,3e-4,0.7\n0.007,3e-4,0.7\n0.008,3e-4,0.7\n");
        ImportDialog d({path});
        QVERIFY(waitIdle(d));
        QVERIFY(!d.isValid());
        io::Run run;
        io::DatasetError err;
        QVERIFY(!io::loadRun(path.toStdString(), io::ColumnMapping{}, run, err));
        QCOMPARE(d.errorText(), QString::fromStdString(err.what()));   // "…:7:1: time does not increase …"
        QCOMPARE(err.line, 7L);

        const QString good = dir.filePath("good.csv");
        writeText(good, "time_s,stage_disp_m,Fx\n0,1e-4,0.5\n0.001,2e-4,0.6\n0.002,3e-4,0.7\n0.003,3e-4,0.7\n"
                        "0.004,3e-4,0.7\n0.005,3e-4,0.7\n0.006,3e-4,0.7\n0.007,3e-4,0.7\n");
        const QString other = dir.filePath("other.csv");
        writeText(other, "time_s,stage_disp_m,friction_force_N\n0,1e-4,0.5\n0.001,2e-4,0.6\n0.002,3e-4,0.7\n"
                         "0.003,3e-4,0.7\n0.004,3e-4,0.7\n0.005,3e-4,0.7\n0.006,3e-4,0.7\n0.007,3e-4,0.7\n");
        d.setFiles({good, other});
        QVERIFY(waitIdle(d));
        d.setColumn(Signal::Friction, "Fx");   // present in good.csv only
        QVERIFY(waitIdle(d));
        QVERIFY(!d.isValid());
        io::ColumnMapping m;
        QVERIFY(m.addColumns("friction=Fx", nullptr));
        QVERIFY(!io::loadRun(other.toStdString(), m, run, err));
        QCOMPARE(d.errorText(), QString::fromStdString(err.what()));   // "other.csv:1: no column 'Fx' …"

        // A unit of the wrong dimension.
        d.setFiles({good});
        QVERIFY(waitIdle(d));
        d.setColumn(Signal::Friction, "Fx");
        d.setUnit(Signal::Friction, "mm");
        QVERIFY(waitIdle(d));
        QVERIFY(!d.isValid());
        QVERIFY2(d.errorText().contains("friction"), qPrintable(d.errorText()));
        d.setUnit(Signal::Friction, "N");
        QVERIFY(waitIdle(d));
        QVERIFY2(d.isValid(), qPrintable(d.errorText()));

        // Per-run settings naming no loaded file, and a manifest without the run.
        d.setRunSets({"nosuch.csv:tN=5N"});
        QVERIFY(waitIdle(d));
        QVERIFY(!d.isValid());
        QVERIFY(d.errorText().contains("no loaded run is called 'nosuch.csv'"));
        d.setRunSets({"good.csv:tN=5N"});
        QVERIFY(waitIdle(d));
        QVERIFY2(d.isValid(), qPrintable(d.errorText()));
        QCOMPARE(d.datasetOptions().runSets, std::vector<std::string>{"good.csv:tN=5N"});
        d.setManifestPath(kShared + "/data/synthetic/D05/manifest.json");
        QVERIFY(waitIdle(d));
        QVERIFY(!d.isValid());
        QVERIFY(d.errorText().contains("lists no run for data file 'good.csv'"));
    }

    void rawVersusCleanedIsPreprocessRunOutput() {
        ImportDialog d({syntheticRun()});
        QSignalSpy updated(&d, &ImportDialog::cleaningUpdated);
        QVERIFY(waitIdle(d));
        QVERIFY(updated.count() >= 1);
        QVERIFY2(d.cleaningPreview().ok, qPrintable(d.cleaningPreview().error));

        io::Dataset ds;
        io::DatasetError err;
        QVERIFY(io::loadDataset(toStd(d.files()), d.datasetOptions(), ds, err));
        auto check = [&](Signal s, double factor) {
            identify::CleanRun clean;
            std::string why;
            QVERIFY(identify::preprocessRun(ds.runs.front(), d.preprocessSettings(), clean, &why));
            d.setPlotSignal(s);
            const QwtPlotCurve* cleaned = d.comparePlot()->curve("cleaned");
            const QwtPlotCurve* raw = d.comparePlot()->curve("raw");
            QVERIFY(cleaned && raw);
            const auto cs = samplesOf(cleaned);
            const auto rs = samplesOf(raw);
            QCOMPARE(cs.size(), clean.run[s].size());
            QCOMPARE(rs.size(), ds.runs.front()[s].size());
            for (size_t i = 0; i < cs.size(); ++i) {
                QCOMPARE(cs[i].x(), clean.run[Signal::Time][i]);
                QCOMPARE(cs[i].y(), clean.run[s][i] * factor);
            }
            for (size_t i = 0; i < rs.size(); ++i) QCOMPARE(rs[i].y(), ds.runs.front()[s][i] * factor);
            QVERIFY(d.comparePlot()->hasWindow());
            QCOMPARE(d.comparePlot()->comparison().windowBegin_s, clean.run[Signal::Time][clean.begin]);
            QCOMPARE(d.comparePlot()->comparison().windowEnd_s, clean.run[Signal::Time][clean.end - 1]);
        };
        check(Signal::Friction, 1.0);
        check(Signal::StageDisp, 1e3);   // shown in mm

        // Other settings: the plot follows (computed off the GUI thread).
        identify::PreprocessSettings s = d.preprocessSettings();
        s.filters.lowPass_Hz = 30.0;
        s.filters.bandStop = false;
        s.trim.start_s = 0.5;
        const int before = updated.count();
        d.setPreprocessSettings(s);
        QVERIFY(waitIdle(d));
        QVERIFY(updated.count() > before);
        QCOMPARE(d.preprocessSettings().filters.lowPass_Hz, 30.0);
        QVERIFY(!d.preprocessSettings().filters.bandStop);
        check(Signal::Friction, 1.0);
        check(Signal::SliderDisp, 1e3);

        // The slider state fused with its acceleration (opt-in): the plot shows what
        // preprocessRun gives with it, and the run's notes name the smoother's levels.
        QVERIFY(!d.preprocessSettings().fuseSliderAcceleration);
        s.fuseSliderAcceleration = true;
        d.setPreprocessSettings(s);
        QVERIFY(waitIdle(d));
        QVERIFY(d.preprocessSettings().fuseSliderAcceleration);
        check(Signal::SliderDisp, 1e3);
        bool named = false;
        for (const std::string& n : d.cleaningPreview().clean.notes) named = named || n.find("RTS smoother") != std::string::npos;
        QVERIFY(named);

        // A derived signal (relative velocity) has no raw curve.
        d.setPlotSignal(Signal::RelVel);
        QVERIFY(d.comparePlot()->curve("cleaned"));
        QVERIFY(!d.comparePlot()->curve("raw"));

        // Cleaning settings the sampling rate cannot carry are refused with the reason.
        s.filters.lowPass_Hz = 600.0;   // above Nyquist at 1 kHz
        d.setPreprocessSettings(s);
        QVERIFY(waitIdle(d));
        QVERIFY(!d.isValid());
        QVERIFY2(d.errorText().contains("low-pass cut-off"), qPrintable(d.errorText()));
    }

    void screenshot() {
        // Saved only on request (STICKSLIP_SCREENSHOT_DIR), to look at the layout.
        const QByteArray out = qgetenv("STICKSLIP_SCREENSHOT_DIR");
        if (out.isEmpty()) QSKIP("set STICKSLIP_SCREENSHOT_DIR to save screenshots");
        ImportDialog d({syntheticRun(), kShared + "/data/synthetic/D05/run_02.csv"});
        d.show();
        QVERIFY(waitIdle(d));
        QVERIFY(d.grab().save(QString::fromLocal8Bit(out) + "/import_dialog.png"));
        auto* tabs = d.findChild<QTabWidget*>();
        QVERIFY(tabs);
        tabs->setCurrentIndex(1);
        QTest::qWait(50);
        QVERIFY(d.grab().save(QString::fromLocal8Bit(out) + "/import_dialog_cleaning.png"));
        ImportDialog bad({damperRun(), QStringLiteral("/nonexistent/run.csv")});
        bad.show();
        QVERIFY(waitIdle(bad));
        QVERIFY(bad.grab().save(QString::fromLocal8Bit(out) + "/import_dialog_error.png"));
    }
};

QTEST_MAIN(TstImportDialog)
#include "tst_import_dialog.moc"
