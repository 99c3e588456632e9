// The physical ranges of measured and prescribed signals (core/io/channel_ranges.hpp): each
// rule, applied by every reader of a user's data with file:line:column, the value as written
// and the allowed range; and every shipped data file still loads.
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/io/channel_ranges.hpp"
#include "core/io/csv_table.hpp"
#include "core/io/dataset.hpp"
#include "core/io/run_csv.hpp"

using namespace stickslip;
using namespace stickslip::io;

namespace {

const std::string kShared = STICKSLIP_SHARED_DIR;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// A measured run of 8 rows (loadRun needs at least 8) with `cell` as the friction force of row 6.
std::string runText(const std::string& cell) {
    std::string s = "# rig\ntime_s,stage_disp_m,friction_force_N\n";
    for (int i = 0; i < 8; ++i)
        s += std::to_string(i * 0.001) + ",1e-4," + (i == 5 ? cell : std::string("0.5")) + "\n";
    return s;
}

}  // namespace

class TstChannelRanges : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;

    std::string write(const std::string& name, const std::string& text) {
        const std::string path = dir_.filePath(QString::fromStdString(name)).toStdString();
        std::ofstream(path, std::ios::binary) << text;
        return path;
    }

private slots:
    void tableHasEveryChannelOnce() {
        const auto& t = channelRanges();
        QCOMPARE(t.size(), size_t(6));
        for (size_t i = 0; i < t.size(); ++i) {
            QCOMPARE(static_cast<size_t>(t[i].channel), i);
            QCOMPARE(&channelRange(t[i].channel), &t[i]);
            QVERIFY(t[i].min < t[i].max);
            QVERIFY(std::string(t[i].doc).size() > 10);
        }
        QCOMPARE(channelRange(Channel::Displacement).rangeText(), std::string("[-10, 10] m"));
        QCOMPARE(channelRange(Channel::Force).rangeText(), std::string("[-1e+06, 1e+06] N"));
        QCOMPARE(channelRange(Channel::NormalForce).rangeText(), std::string("[0, 1e+06] N"));
    }

    void eachRuleOnItsBounds_data() {
        QTest::addColumn<int>("channel");
        QTest::addColumn<double>("inside");
        QTest::addColumn<double>("outside");
        QTest::newRow("time") << int(Channel::Time) << 1e9 << 1.0000001e9;
        QTest::newRow("displacement") << int(Channel::Displacement) << -10.0 << -10.0000001;
        QTest::newRow("velocity") << int(Channel::Velocity) << 1e3 << 1.0000001e3;
        QTest::newRow("acceleration") << int(Channel::Acceleration) << -1e6 << -1.0000001e6;
        QTest::newRow("force") << int(Channel::Force) << 1e6 << 1.0000001e6;
        QTest::newRow("normal") << int(Channel::NormalForce) << 0.0 << -1e-9;
    }
    void eachRuleOnItsBounds() {
        QFETCH(int, channel);
        QFETCH(double, inside);
        QFETCH(double, outside);
        const auto c = static_cast<Channel>(channel);
        ValueProblem p;
        QVERIFY(checkChannel(c, "x", {inside}, p));
        QVERIFY(!checkChannel(c, "x", {inside, outside}, p));
        QCOMPARE(p.row, size_t(1));
        QVERIFY2(contains(p.message, "x = " + shortestNumber(outside)), p.message.c_str());
        QVERIFY2(contains(p.message, channelRange(c).rangeText()), p.message.c_str());
        for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()}) {
            QVERIFY(!checkChannel(c, "x", {inside, inside, bad}, p) || c == Channel::Time);
            if (c != Channel::Time) QCOMPARE(p.row, size_t(2));
        }
    }

    void timeFiniteAndStrictlyIncreasing() {
        ValueProblem p;
        QVERIFY(checkChannel(Channel::Time, "t", {-1.0, 0.0, 1e-9, 5.0}, p));
        QVERIFY(!checkChannel(Channel::Time, "t", {0.0, 0.001, 0.001, 0.002}, p));  // duplicate
        QCOMPARE(p.row, size_t(2));
        QVERIFY2(contains(p.message, "time does not increase"), p.message.c_str());
        QVERIFY(!checkChannel(Channel::Time, "t", {0.0, 0.002, 0.001}, p));  // backwards
        QCOMPARE(p.row, size_t(2));
        QVERIFY(!checkChannel(Channel::Time, "t", {0.0, std::numeric_limits<double>::quiet_NaN()}, p));
        QCOMPARE(p.row, size_t(1));
        QVERIFY(!checkChannel(Channel::Time, "t", {0.0, std::numeric_limits<double>::infinity()}, p));
    }

    void valueShownAsWritten() {
        ValueProblem p;
        // 2e7 mm read with --units slip=mm is 2e4 m in SI: the message shows both.
        QVERIFY(!checkChannel(Channel::Displacement, "g", {1e-3, 2e4}, p, 1e-3, "mm"));
        QVERIFY2(contains(p.message, "g = 2e+07 mm (20000 m)"), p.message.c_str());
        QVERIFY2(contains(p.message, "[-10, 10] m"), p.message.c_str());
    }

    void cellColumnsPointAtCells() {
        CsvTable t;
        CsvError e;
        QVERIFY(parseCsvTable("# c\na;bb;c\n1;  22;3\n\n444;5;66\n", "t.csv", t, e));
        QCOMPARE(t.cellColumns.size(), size_t(6));
        QCOMPARE(t.cellColumn(0, 0), 1L);
        QCOMPARE(t.cellColumn(0, 1), 3L);  // where the field starts, blanks included
        QCOMPARE(t.cellColumn(0, 2), 8L);
        QCOMPARE(t.cellColumn(1, 1), 5L);
        QCOMPARE(t.cellColumn(1, 2), 7L);
        QCOMPARE(t.rowLines[1], 5L);
        QCOMPARE(t.cellColumn(2, 0), 0L);  // no such row
        QCOMPARE(t.cellColumn(0, 3), 0L);  // no such column
    }

    // The issue's case: a slip of 1e300 m in a prescribed history is rejected by the reader.
    void slipHistoryRejectsAbsurdSlip() {
        const std::string f = write("absurd.csv", "# slip\ntime_s,rel_disp_m\n0,0\n0.001,1e-6\n0.002,1e300\n");
        SlipHistory h;
        CsvError e;
        QVERIFY(!readSlipHistoryCsv(f, h, e));
        QVERIFY(h.t_s.empty());
        QCOMPARE(e.line, 5L);
        QCOMPARE(e.column, 7L);
        QVERIFY2(contains(e.what(), f + ":5:7: rel_disp_m = 1e+300 m is outside the allowed range [-10, 10] m"),
                 e.what().c_str());
    }

    void slipHistoryRulesPerColumn_data() {
        QTest::addColumn<QString>("text");
        QTest::addColumn<long>("line");
        QTest::addColumn<long>("column");
        QTest::addColumn<QString>("part");
        QTest::newRow("stage_disp") << "time_s,stage_disp_m\n0,0\n1,-11\n" << 3L << 3L << "stage_disp_m = -11 m";
        QTest::newRow("velocity") << "time_s,rel_vel_mps\n0,0\n1,5e3\n" << 3L << 3L << "rel_vel_mps = 5000 m/s";
        QTest::newRow("integrated slip") << "time_s,rel_vel_mps\n0,900\n1,900\n" << 3L << 3L
                                         << "slip integrated from rel_vel_mps = 900 m";
        QTest::newRow("normal force") << "time_s;rel_disp_m;normal_force_N\n0;0;5\n1;0;2e7\n" << 3L << 5L
                                      << "normal_force_N = 2e+07 N is outside the allowed range [0, 1e+06] N";
        QTest::newRow("normal zero") << "time_s,rel_disp_m,normal_force_N\n0,0,5\n1,0,0\n" << 3L << 5L
                                     << "normal_force_N must be > 0";
        QTest::newRow("time huge") << "time_s,rel_disp_m\n0,0\n1e12,0\n" << 3L << 1L << "time_s = 1e+12 s";
        QTest::newRow("time duplicate") << "rel_disp_m,time_s\n0,0\n0,1\n0,1\n" << 4L << 3L << "time does not increase";
    }
    void slipHistoryRulesPerColumn() {
        QFETCH(QString, text);
        QFETCH(long, line);
        QFETCH(long, column);
        QFETCH(QString, part);
        CsvTable t;
        CsvError e;
        QVERIFY2(parseCsvTable(text.toStdString(), "h.csv", t, e), e.what().c_str());
        SlipHistory h;
        QVERIFY(!slipHistoryFromTable(t, h, e));
        QCOMPARE(e.line, line);
        QCOMPARE(e.column, column);
        QVERIFY2(contains(e.what(), "h.csv:" + std::to_string(line) + ":" + std::to_string(column) + ": "), e.what().c_str());
        QVERIFY2(contains(e.message, part.toStdString()), e.message.c_str());
    }

    void measuredRunRejectsOutOfRange() {
        Run r;
        r.file = "untouched";
        DatasetError err;
        const std::string f = write("force.csv", runText("3e6"));
        QVERIFY(!loadRun(f, ColumnMapping{}, r, err));
        QCOMPARE(r.file, std::string("untouched"));
        QCOMPARE(err.line, 8L);  // comment, header, then row 6
        QCOMPARE(err.column, 15L);
        QVERIFY2(contains(err.what(), f + ":8:15: friction_force_N = 3e+06 N is outside the allowed range [-1e+06, 1e+06] N"),
                 err.what().c_str());
        QVERIFY(loadRun(write("ok.csv", runText("-9e5")), ColumnMapping{}, r, err));
    }

    // Ranges apply in SI after unit conversion; the message shows the value as written.
    void measuredRunRangeAfterUnits() {
        const std::string f = write("kN.csv", runText("900"));
        ColumnMapping m;
        std::string why;
        QVERIFY2(m.addUnits("friction=kN", &why), why.c_str());
        Run r;
        DatasetError err;
        QVERIFY2(loadRun(f, m, r, err), err.what().c_str());  // 900 kN = 9e5 N: inside
        QCOMPARE(r[Signal::Friction][5], 9e5);
        const std::string g = write("kN2.csv", runText("2000"));
        QVERIFY(!loadRun(g, m, r, err));  // 2000 kN = 2e6 N: outside
        QVERIFY2(contains(err.message, "friction_force_N = 2000 kN (2e+06 N)"), err.message.c_str());
        // And the other way round: 5e3 mm = 5 m is fine although the number exceeds 10.
        QVERIFY(m.addUnits("stage_disp=mm", &why));
        std::string s = "time_s,stage_disp_m\n";
        for (int i = 0; i < 8; ++i) s += std::to_string(i) + ",5e3\n";
        QVERIFY2(loadRun(write("mm.csv", s), m, r, err), err.what().c_str());
    }

    void measuredRunTimeRules() {
        std::string s = "time_s,friction_force_N\n";
        for (int i = 0; i < 8; ++i) s += std::to_string(i == 4 ? 3 : i) + ",1\n";
        Run r;
        DatasetError err;
        QVERIFY(!loadRun(write("dup.csv", s), ColumnMapping{}, r, err));
        QCOMPARE(err.line, 6L);
        QCOMPARE(err.column, 1L);
        QVERIFY2(contains(err.message, "time does not increase (3.000000 s then 3.000000 s)"), err.message.c_str());
    }

    void manifestSettingsInRange() {
        Manifest m;
        DatasetError err;
        const std::string f = write("m.json", R"({"runs": [{"file": "run_01.csv", "A_m": 1e300, "tN_N": 6.2}]})");
        QVERIFY(!readManifest(f, m, err));
        QVERIFY2(contains(err.what(), f + ": manifest run run_01.csv: A_m = 1e+300 m is outside the allowed range [-10, 10] m"),
                 err.what().c_str());
        const std::string g = write("n.json", R"({"runs": [{"file": "run_01.csv", "A_m": 0.001, "tN_N": 2e7}]})");
        QVERIFY(!readManifest(g, m, err));
        QVERIFY2(contains(err.message, "tN_N = 2e+07 N is outside the allowed range [0, 1e+06] N"), err.message.c_str());
        const std::string h = write("o.json", R"({"runs": [{"file": "run_01.csv", "A_m": 0.001, "tN_N": 6.2, "k_N_per_m": 8446}]})");
        QVERIFY2(readManifest(h, m, err), err.what().c_str());
        QCOMPARE(m.runs["run_01.csv"]["k"], 8446.0);
    }

    // Every real measurement and every synthetic set shipped in shared/data loads through the
    // readers with the range checks.
    void shippedDataStillLoads() {
        namespace fs = std::filesystem;
        int files = 0;
        for (const auto& e : fs::directory_iterator(kShared + "/data/real/friction-damper")) {
            if (e.path().extension() != ".csv") continue;
            Dataset ds;
            DatasetError err;
            QVERIFY2(loadDataset({e.path().string()}, DatasetOptions{}, ds, err), err.what().c_str());
            ++files;
        }
        QVERIFY(files >= 12);
        int sets = 0;
        for (const auto& d : fs::directory_iterator(kShared + "/data/synthetic")) {
            if (!fs::exists(d.path() / "manifest.json")) continue;
            std::vector<std::string> runs;
            for (const auto& e : fs::directory_iterator(d.path()))
                if (e.path().extension() == ".csv") runs.push_back(e.path().string());
            DatasetOptions o;
            o.manifestPath = (d.path() / "manifest.json").string();
            Dataset ds;
            DatasetError err;
            QVERIFY2(loadDataset(runs, o, ds, err), err.what().c_str());
            files += static_cast<int>(runs.size());
            ++sets;
        }
        QCOMPARE(sets, 18);
        qInfo("%d shipped data files load", files);
    }
};

QTEST_APPLESS_MAIN(TstChannelRanges)
#include "tst_channel_ranges.moc"
