// stickslip-cli simulate and presets, run as a separate process: CSV output, exit codes
// and messages, prescribed slip from a file.
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>
#include <fstream>

#include "core/analysis/sweep.hpp"
#include "core/integrate/adaptive.hpp"
#include "core/integrate/simulate.hpp"
#include "core/io/csv_table.hpp"
#include "core/io/run_csv.hpp"
#include "core/presets.hpp"

#include "cli_runner.hpp"
#include "tests/file_bytes.hpp"

using namespace stickslip;

namespace {

using Result = stickslip::testing::CliResult;

using stickslip::testing::runCli;

void writeText(const QString& path, const std::string& text) {
    std::ofstream f(path.toStdString(), std::ios::binary);
    f << text;
}

}  // namespace

class TstCliSimulate : public QObject {
    Q_OBJECT
private slots:
    void helpOnCommands() {
        for (const char* cmd : {"simulate", "presets"}) {
            const Result r = runCli({cmd, "--help"});
            QCOMPARE(r.exitCode, 0);
            QVERIFY(r.out.contains("--help"));
        }
        const Result r = runCli({"simulate", "--help"});
        for (const char* opt : {"--preset", "--model", "--setup", "--set", "--cycles", "--transient", "--dt",
                                "--output-every", "--input", "--out"})
            QVERIFY2(r.out.contains(opt), opt);
    }

    void presetsListsPaperSets() {
        const Result r = runCli({"presets"});
        QCOMPARE(r.exitCode, 0);
        for (const char* name : {"default", "fig16", "fig17", "fig18", "fig19", "fig20", "fig22", "fig23"})
            QVERIFY2(r.out.contains(QByteArray("\n") + name) || r.out.startsWith(name), name);
        QVERIFY(r.out.contains("k = 8446 N/m"));
        const Result one = runCli({"presets", "fig19"});
        QCOMPARE(one.exitCode, 0);
        QVERIFY2(one.out.contains("k = 3034 N/m"), one.out.constData());
        QVERIFY(one.out.contains("epsT = 11000 N/m"));
        const Result bad = runCli({"presets", "fig99"});
        QCOMPARE(bad.exitCode, 2);
        QVERIFY(bad.err.contains("fig99"));
    }

    // The CSV equals an in-process core run with the same parameters.
    void writesCsvEqualToCoreRun() {
        QTemporaryDir dir;
        const QString out = dir.filePath("fig20.csv");
        const Result r = runCli({"simulate", "--preset", "fig20", "--cycles", "2", "--set", "A=0.0008", "--set",
                                 "eta=0.5s/m", "--out", out});
        QVERIFY2(r.exitCode == 0, r.err.constData());
        io::CsvTable t;
        io::CsvError e;
        QVERIFY2(io::readCsvTable(out.toStdString(), t, e), e.what().c_str());
        QCOMPARE(t.header, io::runCsvColumns());

        Preset pr;
        QVERIFY(findPreset("fig20", pr));
        SimParams p = pr.params;
        p.cycles = 2;
        p.drive.amplitude_m = 0.0008;
        p.lawParams<RateStateParams>().eta_s_per_m = 0.5;
        const RunResult ref = simulate(p);
        QVERIFY2(ref.ok(), ref.message.c_str());
        QCOMPARE(t.rows(), ref.samples.size());
        const int ix = t.column("slider_disp_m"), iF = t.column("friction_force_N"), is = t.column("stuck");
        double maxErrX = 0, maxX = 0;
        for (size_t i = 0; i < ref.samples.size(); ++i) {
            maxErrX = std::max(maxErrX, std::abs(t.columns[ix][i] - ref.samples[i].slider_m));
            maxX = std::max(maxX, std::abs(ref.samples[i].slider_m));
            QVERIFY(std::abs(t.columns[iF][i] - ref.samples[i].force_N) <= 1e-9 * std::max(1.0, std::abs(ref.samples[i].force_N)));
            QCOMPARE(t.columns[is][i], ref.samples[i].stuck ? 1.0 : 0.0);
        }
        QVERIFY(maxX > 0);
        QVERIFY(maxErrX <= 1e-9 * maxX);
        // Header lines carry the parameters as set, with units, and the version.
        bool sawA = false, sawVersion = false;
        for (const std::string& c : t.comments) {
            sawA |= c == "A = 0.0008 m";
            sawVersion |= c.rfind("version = ", 0) == 0;
        }
        QVERIFY(sawA);
        QVERIFY(sawVersion);
    }

    // --tolerance selects the adaptive integrator (core/integrate/adaptive.hpp): the CSV equals
    // the in-process simulateAdaptive run, on the exact --output-every grid, and says so in a
    // header line; an out-of-range tolerance or one in the prescribed set-up is exit 2.
    void toleranceSelectsAdaptive() {
        QTemporaryDir dir;
        const QString out = dir.filePath("adaptive.csv");
        const Result r = runCli({"simulate", "--preset", "fig20", "--cycles", "2", "--tolerance", "1e-4",
                                 "--output-every", "0.001", "--out", out});
        QVERIFY2(r.exitCode == 0, r.err.constData());
        io::CsvTable t;
        io::CsvError e;
        QVERIFY2(io::readCsvTable(out.toStdString(), t, e), e.what().c_str());
        Preset pr;
        QVERIFY(findPreset("fig20", pr));
        SimParams p = pr.params;
        p.cycles = 2;
        p.integration.outputInterval_s = 0.001;
        AdaptiveOptions o;
        o.tolerance = 1e-4;
        const RunResult ref = simulateAdaptive(p, o);
        QVERIFY2(ref.ok(), ref.message.c_str());
        QCOMPARE(t.rows(), ref.samples.size());
        const int it = t.column("time_s"), ix = t.column("slider_disp_m");
        for (size_t i = 0; i < ref.samples.size(); ++i) {
            QVERIFY(std::abs(t.columns[it][i] - 0.001 * static_cast<double>(i)) <= 1e-12);
            QVERIFY(std::abs(t.columns[ix][i] - ref.samples[i].slider_m) <= 1e-12);
        }
        bool saw = false;
        for (const std::string& c : t.comments) saw |= c.rfind("integration = adaptive, tolerance = 0.0001", 0) == 0;
        QVERIFY(saw);
        QCOMPARE(runCli({"simulate", "--tolerance", "1e-7", "--out", dir.filePath("x.csv")}).exitCode, 2);
        QCOMPARE(runCli({"simulate", "--tolerance", "abc", "--out", dir.filePath("x.csv")}).exitCode, 2);
        QCOMPARE(runCli({"simulate", "--setup", "prescribed", "--tolerance", "1e-3", "--out", dir.filePath("x.csv")}).exitCode, 2);
    }

    // sweep and map take --tolerance too: the summary equals the in-process adaptive sweep and its
    // header says how it was stepped; the Lyapunov exponent (fixed-step map) with a tolerance is
    // refused with exit 2, naming the tolerance.
    void sweepAndMapTakeATolerance() {
        QTemporaryDir dir;
        const QString out = dir.filePath("s.csv"), sum = dir.filePath("sum.csv");
        const Result r = runCli({"sweep", "--preset", "fig20", "--from", "0.5mm", "--to", "3mm", "--steps", "3",
                                 "--settle", "20", "--samples", "20", "--no-lyapunov", "--tolerance", "1e-4", "--out", out,
                                 "--summary", sum});
        QVERIFY2(r.exitCode == 0, r.err.constData());
        // The summary has text columns (direction, class): read it line by line.
        QList<QByteArray> rows;
        bool saw = false;
        for (const QByteArray& line : readAll(sum).split('\n')) {
            if (line.startsWith('#')) saw |= line.contains("integration = adaptive, tolerance = 0.0001");
            else if (!line.isEmpty() && !line.startsWith("param_value")) rows.push_back(line);
        }
        QVERIFY(saw);
        Preset pr;
        QVERIFY(findPreset("fig20", pr));
        SimParams p = pr.params;
        p.integration.tolerance = 1e-4;
        SweepOptions so;
        so.from = 0.5e-3;
        so.to = 3e-3;
        so.steps = 3;
        so.settleCycles = 20;
        so.sampleCycles = 20;
        so.lyapunov = false;
        const SweepResult ref = bifurcationSweep(p, so);
        QVERIFY2(ref.status == RunStatus::Ok, ref.message.c_str());
        QCOMPARE(size_t(rows.size()), ref.points.size());
        for (size_t i = 0; i < ref.points.size(); ++i) {
            const QList<QByteArray> f = rows[static_cast<int>(i)].split(',');
            QCOMPARE(f.size(), 7);
            QCOMPARE(QString(f[2]), QString(toString(ref.points[i].classification.motion)));
            QVERIFY(std::abs(f[4].toDouble() - ref.points[i].classification.stickFraction) <= 1e-9);
        }
        const Result lyap = runCli({"sweep", "--preset", "fig20", "--from", "1mm", "--to", "2mm", "--steps", "2",
                                    "--tolerance", "1e-4", "--out", out});
        QCOMPARE(lyap.exitCode, 2);
        QVERIFY2(lyap.err.contains("tolerance"), lyap.err.constData());
        const QString map = dir.filePath("map.csv");
        const Result m = runCli({"map", "--preset", "fig20", "--param", "A", "--from", "0.5mm", "--to", "3mm", "--steps",
                                 "2", "--param2", "f", "--from2", "2.5", "--to2", "3.5", "--steps2", "2", "--settle", "20",
                                 "--samples", "20", "--tolerance", "1e-4", "--out", map});
        QVERIFY2(m.exitCode == 0, m.err.constData());
        QVERIFY(readAll(map).contains("integration = adaptive, tolerance = 0.0001"));
    }

    // reproduce --tolerance: the figure's section and run are integrated adaptively (the section
    // at the exact phase: sample k at (settle + k) T), and the files say so.
    void reproduceTakesATolerance() {
        QTemporaryDir dir;
        const Result r = runCli({"reproduce", "--figure", "22", "--tolerance", "1e-4", "--settle", "3", "--cycles", "2",
                                 "--section-points", "4", "--out", dir.path()});
        if (r.err.contains("no plot widgets")) QSKIP("stickslip-cli built without plot widgets: no reproduce");
        QVERIFY2(r.exitCode == 0, r.err.constData());
        const QByteArray sec = readAll(dir.filePath("fig22_poincare.csv"));
        QVERIFY2(sec.contains("integration = adaptive, tolerance = 0.0001"), sec.left(300).constData());
        QCOMPARE(runCli({"reproduce", "--figure", "22", "--tolerance", "1e-7", "--out", dir.path()}).exitCode, 2);
    }

    void outDashWritesStdout() {
        const Result r = runCli({"simulate", "--preset", "fig16", "--cycles", "1", "--out", "-"});
        QVERIFY2(r.exitCode == 0, r.err.constData());
        QVERIFY(r.out.startsWith("# StickSlip Lab"));
        QVERIFY(r.out.contains("\ntime_s,stage_disp_m,slider_disp_m,slider_vel_mps,rel_vel_mps,friction_force_N,"
                               "friction_ratio,state_alpha,stuck\n"));
        io::CsvTable t;
        io::CsvError e;
        QVERIFY2(io::parseCsvTable(r.out.toStdString(), "stdout", t, e), e.what().c_str());
        QVERIFY(t.rows() > 100);
        // fig16 is prescribed slip: the slider is held.
        for (double x : t.columns[t.column("slider_disp_m")]) QCOMPARE(x, 0.0);
    }

    void badParametersExit2_data() {
        QTest::addColumn<QStringList>("args");
        QTest::addColumn<QString>("mentions");
        QTest::newRow("unknown key") << QStringList{"--set", "zeta=1"} << "zeta";
        QTest::newRow("wrong unit") << QStringList{"--set", "A=3Hz"} << "A = 3Hz";
        QTest::newRow("negative tN") << QStringList{"--set", "tN=-1N"} << "tN = -1";
        QTest::newRow("zero mass") << QStringList{"--set", "m=0"} << "m = 0";
        QTest::newRow("no equals") << QStringList{"--set", "A"} << "KEY=VALUE";
        QTest::newRow("bad model") << QStringList{"--model", "lugre"} << "lugre";
        QTest::newRow("bad setup") << QStringList{"--setup", "both"} << "both";
        QTest::newRow("bad preset") << QStringList{"--preset", "fig99"} << "fig99";
        QTest::newRow("bad dt") << QStringList{"--dt", "-1"} << "dt";
        QTest::newRow("dt wrong unit") << QStringList{"--dt", "1mm"} << "dt = 1mm";
        QTest::newRow("input with dynamics") << QStringList{"--setup", "dynamics", "--input", "x.csv"} << "--input";
        QTest::newRow("unknown option") << QStringList{"--frobnicate"} << "frobnicate";
    }
    void badParametersExit2() {
        QFETCH(QStringList, args);
        QFETCH(QString, mentions);
        QTemporaryDir dir;
        const QString out = dir.filePath("never.csv");
        const Result r = runCli(QStringList{"simulate", "--out", out} + args);
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains(mentions.toUtf8()), r.err.constData());
        QVERIFY(!QFile::exists(out));
    }

    void unwritableOutputExit3() {
        const Result r = runCli({"simulate", "--preset", "fig16", "--cycles", "1", "--out", "/nonexistent/dir/o.csv"});
        QCOMPARE(r.exitCode, 3);
        QVERIFY2(r.err.contains("/nonexistent/dir/o.csv"), r.err.constData());
    }

    // --model coulomb reaches the run: the header says so, and with t_N F/t_N never exceeds μ
    // by more than the penalty allows (|F| <= μ t_N in the elasto-plastic Coulomb law).
    void coulombModel() {
        const Result r = runCli({"simulate", "--preset", "fig20", "--model", "coulomb", "--set", "mu=0.3",
                                 "--cycles", "2", "--out", "-"});
        QVERIFY2(r.exitCode == 0, r.err.constData());
        QVERIFY(r.out.contains("\n# model = coulomb\n"));
        QVERIFY(r.out.contains("\n# mu = 0.3\n"));
        io::CsvTable t;
        io::CsvError e;
        QVERIFY2(io::parseCsvTable(r.out.toStdString(), "stdout", t, e), e.what().c_str());
        double maxRatio = 0;
        for (double q : t.columns[t.column("friction_ratio")]) maxRatio = std::max(maxRatio, std::abs(q));
        QVERIFY2(maxRatio <= 0.3 * (1 + 1e-9), qPrintable(QString::number(maxRatio, 'g', 12)));
        QVERIFY(maxRatio > 0.29);  // A = 1 mm at 3 Hz drives the slider into slip
    }

    void missingOutIsBadArgument() {
        const Result r = runCli({"simulate", "--preset", "fig16"});
        QCOMPARE(r.exitCode, 2);
        QVERIFY(r.err.contains("--out"));
    }

    void malformedInputExit3() {
        QTemporaryDir dir;
        const QString in = dir.filePath("bad.csv");
        writeText(in, "# slip history\ntime_s,rel_disp_m\n0,0\n0.001,1e-6\n0.002,oops\n");
        const Result r = runCli({"simulate", "--setup", "prescribed", "--input", in, "--out", dir.filePath("o.csv")});
        QCOMPARE(r.exitCode, 3);
        QVERIFY2(r.err.contains((in + ":5:7:").toUtf8()), r.err.constData());
        QVERIFY(!QFile::exists(dir.filePath("o.csv")));

        const Result missing = runCli({"simulate", "--input", dir.filePath("nope.csv"), "--out", "-"});
        QCOMPARE(missing.exitCode, 3);
        QVERIFY(missing.err.contains("nope.csv"));

        writeText(in, "time_s,force_N\n0,0\n1,1\n");
        const Result noColumn = runCli({"simulate", "--input", in, "--out", "-"});
        QCOMPARE(noColumn.exitCode, 3);
        QVERIFY2(noColumn.err.contains("rel_disp_m"), noColumn.err.constData());
    }

    // Absurd values in an input history are rejected by the reader (file:line:column, the
    // value and the allowed range, exit 3), not later by the return map (exit 4).
    void absurdInputValuesExit3() {
        QTemporaryDir dir;
        const QString in = dir.filePath("absurd.csv");
        writeText(in, "# slip history\ntime_s,rel_disp_m\n0,0\n0.001,1e-6\n0.002,1e300\n0.003,2e-6\n");
        const QString out = dir.filePath("o.csv");
        const Result r = runCli({"simulate", "--setup", "prescribed", "--input", in, "--out", out});
        QCOMPARE(r.exitCode, 3);
        QVERIFY2(r.err.contains((in + ":5:7:").toUtf8()), r.err.constData());
        QVERIFY2(r.err.contains("1e+300"), r.err.constData());
        QVERIFY2(r.err.contains("[-10, 10] m"), r.err.constData());
        QVERIFY2(!r.err.contains("return mapping"), r.err.constData());
        QVERIFY(!QFile::exists(out));

        writeText(in, "time_s,rel_disp_m\n0,0\n0.001,1e-6\n0.001,2e-6\n");
        const Result dup = runCli({"simulate", "--input", in, "--out", out});
        QCOMPARE(dup.exitCode, 3);
        QVERIFY2(dup.err.contains((in + ":4:1:").toUtf8()), dup.err.constData());
        QVERIFY2(dup.err.contains("increas"), dup.err.constData());

        writeText(in, "time_s,rel_vel_mps,normal_force_N\n0,0.01,5\n0.001,0.01,5\n0.002,0.01,2e7\n");
        const Result force = runCli({"simulate", "--input", in, "--out", out});
        QCOMPARE(force.exitCode, 3);
        QVERIFY2(force.err.contains((in + ":4:12:").toUtf8()), force.err.constData());
        QVERIFY2(force.err.contains("2e+07"), force.err.constData());
    }

    // A run that needs more steps than --max-steps fails at once with a clear message (exit 4).
    void stepBudgetExit4() {
        const Result r = runCli({"simulate", "--dt", "1e-9", "--cycles", "100", "--max-steps", "1000000", "--out", "-"});
        QCOMPARE(r.exitCode, 4);
        QVERIFY2(r.err.contains("step budget exceeded: the run needs 3.33333e+10 steps, more than max_steps = 1e+06"),
                 r.err.constData());
        const Result bad = runCli({"simulate", "--max-steps", "0", "--out", "-"});
        QCOMPARE(bad.exitCode, 2);
        QVERIFY2(bad.err.contains("--max-steps '0'"), bad.err.constData());
        const Result ok = runCli({"simulate", "--cycles", "1", "--max-steps", "10001", "--out", "-"});
        QVERIFY2(ok.exitCode == 0, ok.err.constData());
    }

    // A velocity history V = const read from a file drives the block into steady sliding;
    // the CLI output equals the core run on the same history and ends at Eq. 5.
    void prescribedFromInput() {
        QTemporaryDir dir;
        const QString in = dir.filePath("slip.csv");
        std::string text = "# constant slip rate\ntime_s;rel_vel_mps\n";
        for (int i = 0; i <= 400; ++i) text += std::to_string(i * 0.0025) + ";0.05\n";
        writeText(in, text);
        const QString out = dir.filePath("o.csv");
        const Result r = runCli({"simulate", "--input", in, "--set", "eta=0.6", "--set", "tN=5N", "--out", out});
        QVERIFY2(r.exitCode == 0, r.err.constData());
        io::CsvTable t;
        io::CsvError e;
        QVERIFY2(io::readCsvTable(out.toStdString(), t, e), e.what().c_str());
        QCOMPARE(t.rows(), size_t(401));
        bool sawSetup = false, sawInput = false;
        for (const std::string& c : t.comments) {
            sawSetup |= c == "setup = prescribed";
            sawInput |= c == "input = " + in.toStdString();
        }
        QVERIFY(sawSetup);
        QVERIFY(sawInput);

        // Same history through the core.
        SlipHistory h;
        QVERIFY2(io::readSlipHistoryCsv(in.toStdString(), h, e), e.what().c_str());
        Preset pr;
        QVERIFY(findPreset("default", pr));
        SimParams p = pr.params;
        p.setup = SetupKind::Prescribed;
        p.lawParams<RateStateParams>().eta_s_per_m = 0.6;
        p.rig.normalForce_N = 5.0;
        const RunResult ref = simulate(p, {}, &h);
        QVERIFY2(ref.ok(), ref.message.c_str());
        const int ir = t.column("friction_ratio");
        QCOMPARE(t.rows(), ref.samples.size());
        for (size_t i = 0; i < t.rows(); ++i)
            QVERIFY(std::abs(t.columns[ir][i] - ref.samples[i].ratio) <= 1e-9 * std::max(1.0, std::abs(ref.samples[i].ratio)));
        // The slip (stage_disp_m column) is the integral of V: 0.05 m/s for 1 s.
        QVERIFY(std::abs(t.columns[t.column("stage_disp_m")].back() - 0.05) < 1e-9);
        // After 1 s at V = 0.05 m/s (2500 D_c of slip) the block slides steadily: Eq. 5,
        // |F|/t_N = μ + K1(−C2 V) + η V with K1(α) = C1 (exp(α/r) − 1).
        const double V = 0.05;
        const auto& rs = p.lawParams<RateStateParams>();
        const double eq5 = rs.mu + rs.C1 * (std::exp(-rs.C2() * V / rs.r) - 1.0) + rs.eta_s_per_m * V;
        QVERIFY2(std::abs(std::abs(t.columns[ir].back()) - eq5) <= 1e-3 * eq5,
                 qPrintable(QString("ratio %1, Eq. 5 %2").arg(t.columns[ir].back()).arg(eq5)));
    }
};

QTEST_GUILESS_MAIN(TstCliSimulate)
#include "tst_cli_simulate.moc"
