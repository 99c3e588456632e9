// Run files: header lines with every parameter, exact columns, full precision; and
// prescribed-slip histories read by column name.
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>
#include <filesystem>

#include "core/integrate/simulate.hpp"
#include "core/io/run_csv.hpp"
#include "core/io/units.hpp"
#include "core/presets.hpp"
#include "core/version.hpp"

using namespace stickslip;
using namespace stickslip::io;

class TstRunCsv : public QObject {
    Q_OBJECT
private slots:
    void writesHeaderAndColumns() {
        SimParams p;
        p.cycles = 1;
        RunResult r;
        Sample s;
        s.t_s = 0.123456789012345;
        s.stage_m = 1.0e-3;
        s.slider_m = -2.5e-4;
        s.sliderVel_mps = 0.01;
        s.relVel_mps = -0.02;
        s.force_N = 1.2345678901;
        s.ratio = s.force_N / 6.2;
        s.alpha = 0.75;
        s.stuck = false;
        r.samples = {s, s};
        r.samples[1].stuck = true;
        const std::string text = runCsvText(p, r, {"input = x.csv"});

        CsvTable t;
        CsvError e;
        QVERIFY2(parseCsvTable(text, "run", t, e), e.what().c_str());
        QCOMPARE(t.header, runCsvColumns());
        QCOMPARE(t.header.front(), std::string("time_s"));
        QCOMPARE(t.header.back(), std::string("stuck"));
        QCOMPARE(t.rows(), size_t(2));
        // %.10g: ten significant digits survive.
        QVERIFY(std::abs(t.columns[0][0] - s.t_s) <= 1e-10 * s.t_s);
        QVERIFY(std::abs(t.columns[5][0] - s.force_N) <= 1e-10 * s.force_N);
        QCOMPARE(t.columns[8][0], 0.0);
        QCOMPARE(t.columns[8][1], 1.0);

        // Every parameter appears as "KEY = VALUE UNIT" and reads back exactly.
        auto findComment = [&](const std::string& prefix) -> std::string {
            for (const std::string& c : t.comments)
                if (c.rfind(prefix, 0) == 0) return c.substr(prefix.size());
            return {};
        };
        for (const std::string& key : paramKeys()) {
            const std::string rest = findComment(key + " = ");
            QVERIFY2(!rest.empty(), key.c_str());
            double expected = 0, got = 0;
            QVERIFY(getParam(p, key, expected));
            std::string err;
            QVERIFY2(parseParamValue(key, rest, got, &err), err.c_str());
            QCOMPARE(got, expected);
        }
        QCOMPARE(findComment("version = "), std::string(kVersion));
        QCOMPARE(findComment("model = "), std::string("rate-state"));
        QCOMPARE(findComment("setup = "), std::string("dynamics"));
        QCOMPARE(findComment("status = "), std::string("ok"));
        QCOMPARE(findComment("input = "), std::string("x.csv"));
        QVERIFY(findComment("k = ").find("N/m") != std::string::npos);
    }

    void coulombReportsItsOwnMu() {
        SimParams p;
        p.law = LawKind::Coulomb;
        p.lawParams<CoulombParams>().mu = 0.4;
        const std::string text = runCsvText(p, RunResult{});
        QVERIFY(text.find("# mu = 0.4\n") != std::string::npos);
        QVERIFY(text.find("# model = coulomb\n") != std::string::npos);
    }

    void writeRunCsvRoundTripsACoreRun() {
        Preset pr;
        QVERIFY(findPreset("fig16", pr));
        pr.params.cycles = 1;
        const RunResult r = simulate(pr.params);
        QVERIFY2(r.ok(), r.message.c_str());
        QTemporaryDir dir;
        const std::string path = dir.filePath("run.csv").toStdString();
        std::string err;
        QVERIFY2(writeRunCsv(path, pr.params, r, &err), err.c_str());
        CsvTable t;
        CsvError e;
        QVERIFY2(readCsvTable(path, t, e), e.what().c_str());
        QCOMPARE(t.rows(), r.samples.size());
        const int iF = t.column("friction_force_N");
        for (size_t i = 0; i < r.samples.size(); ++i)
            QVERIFY(std::abs(t.columns[static_cast<size_t>(iF)][i] - r.samples[i].force_N) <=
                    1e-9 * std::max(1.0, std::abs(r.samples[i].force_N)));
    }

    void runCsvValuesAreTheColumnsOfTheText() {
        Preset pr;
        QVERIFY(findPreset("fig20", pr));
        pr.params.cycles = 1;
        const RunResult r = simulate(pr.params);
        QVERIFY2(r.ok(), r.message.c_str());
        const auto values = runCsvValues(r);
        QCOMPARE(values.size(), runCsvColumns().size());
        QTemporaryDir dir;
        const std::string path = dir.filePath("run.csv").toStdString();
        std::string err;
        QVERIFY2(writeRunCsv(path, pr.params, r, &err), err.c_str());
        CsvTable t;
        CsvError e;
        QVERIFY2(readCsvTable(path, t, e), e.what().c_str());
        for (size_t j = 0; j < values.size(); ++j) {
            const int c = t.column(runCsvColumns()[j]);
            QVERIFY(c >= 0);
            QCOMPARE(values[j].size(), r.samples.size());
            for (size_t i = 0; i < r.samples.size(); ++i) {
                const double a = values[j][i], b = t.columns[static_cast<size_t>(c)][i];
                QVERIFY2(std::abs(a - b) <= 1e-9 * std::max(1e-12, std::abs(a)), runCsvColumns()[j].c_str());
            }
        }
        QCOMPARE(values[8][0], r.samples[0].stuck ? 1.0 : 0.0);
    }

    void slipHistoryFromEachColumnKind() {
        CsvTable t;
        CsvError e;
        SlipHistory h;
        // g given directly.
        QVERIFY(parseCsvTable("# c\ntime_s,rel_disp_m\n0,0\n0.1,1e-3\n0.2,3e-3\n", "g.csv", t, e));
        QVERIFY2(slipHistoryFromTable(t, h, e), e.what().c_str());
        QCOMPARE(h.slip_m.size(), size_t(3));
        QCOMPARE(h.slip_m[2], 3e-3);
        QVERIFY(h.velocity_mps.empty());
        // Stage displacement with the slider held fixed: g = u.
        QVERIFY(parseCsvTable("time_s;stage_disp_m;friction_force_N\n0;1e-3;0\n1;2e-3;0\n", "u.csv", t, e));
        QVERIFY2(slipHistoryFromTable(t, h, e), e.what().c_str());
        QCOMPARE(h.slip_m[1], 2e-3);
        // Velocity, integrated by the trapezoid rule from 0.
        QVERIFY(parseCsvTable("time_s,rel_vel_mps,normal_force_N\n0,0\n,\n", "v.csv", t, e) == false);
        QVERIFY(parseCsvTable("time_s,rel_vel_mps,normal_force_N\n0,0,5\n1,2,5\n2,2,6\n", "v.csv", t, e));
        QVERIFY2(slipHistoryFromTable(t, h, e), e.what().c_str());
        QCOMPARE(h.slip_m[1], 1.0);
        QCOMPARE(h.slip_m[2], 3.0);
        QCOMPARE(h.velocity_mps[2], 2.0);
        QCOMPARE(h.normalForce_N[2], 6.0);
        QVERIFY(h.validate().empty());
    }

    void slipHistoryErrors() {
        CsvTable t;
        CsvError e;
        SlipHistory h;
        h.t_s = {42};
        QVERIFY(parseCsvTable("# x\nt,rel_disp_m\n0,0\n1,1\n", "a.csv", t, e));
        QVERIFY(!slipHistoryFromTable(t, h, e));
        QCOMPARE(e.line, 2L);
        QVERIFY2(e.message.find("time_s") != std::string::npos, e.message.c_str());
        QCOMPARE(h.t_s.size(), size_t(1));  // untouched

        QVERIFY(parseCsvTable("time_s,force\n0,0\n1,1\n", "b.csv", t, e));
        QVERIFY(!slipHistoryFromTable(t, h, e));
        QVERIFY2(e.message.find("rel_vel_mps") != std::string::npos, e.message.c_str());

        QVERIFY(parseCsvTable("time_s,rel_disp_m\n0,0\n1,1\n1,2\n", "c.csv", t, e));
        QVERIFY(!slipHistoryFromTable(t, h, e));
        QCOMPARE(e.line, 4L);
        QCOMPARE(e.column, 1L);
        QVERIFY2(e.what().rfind("c.csv:4:1: ", 0) == 0, e.what().c_str());

        QVERIFY(parseCsvTable("time_s,rel_disp_m,normal_force_N\n0,0,1\n1,1,-1\n", "d.csv", t, e));
        QVERIFY(!slipHistoryFromTable(t, h, e));
        QCOMPARE(e.line, 3L);

        QVERIFY(!readSlipHistoryCsv("/nonexistent/h.csv", h, e));
        QCOMPARE(e.file, std::string("/nonexistent/h.csv"));
    }

    void readsRealDamperFile() {
        const std::string path = std::string(STICKSLIP_SHARED_DIR) + "/data/real/friction-damper/1Hz_30lb_0.5in.csv";
        if (!std::filesystem::exists(path)) QSKIP("shared data not present");
        SlipHistory h;
        CsvError e;
        QVERIFY2(readSlipHistoryCsv(path, h, e), e.what().c_str());
        QVERIFY(h.t_s.size() > 1000);
        QVERIFY(h.validate().empty());
        double maxAbs = 0;
        for (double g : h.slip_m) maxAbs = std::max(maxAbs, std::abs(g));
        // Nominal amplitude 0.5 in = 12.7 mm (the drive is tapered; allow a wide band).
        QVERIFY2(maxAbs > 0.005 && maxAbs < 0.03, qPrintable(QString::number(maxAbs)));
    }
};

QTEST_GUILESS_MAIN(TstRunCsv)
#include "tst_run_csv.moc"
