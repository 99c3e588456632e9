// CSV tables: delimiters, comments, positioned errors, nothing half-loaded, atomic writes.
#include <QTemporaryDir>
#include <QtTest>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/io/csv_table.hpp"

using namespace stickslip::io;

namespace {
std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}
}  // namespace

class TstCsvTable : public QObject {
    Q_OBJECT
private slots:
    void delimiters_data() {
        QTest::addColumn<QString>("text");
        QTest::addColumn<char>("delimiter");
        QTest::newRow("comma") << "t,x\n0,1.5\n1,-2e-3\n" << ',';
        QTest::newRow("semicolon") << "t;x\n0;1.5\n1;-2e-3\n" << ';';
        QTest::newRow("tab") << "t\tx\n0\t1.5\n1\t-2e-3\n" << '\t';
        QTest::newRow("crlf+spaces") << "t , x\r\n0 , 1.5\r\n1, -2e-3\r\n" << ',';
        QTest::newRow("quoted") << "\"t\",\"x\"\n\"0\",\"1.5\"\n1,-2e-3" << ',';
    }
    void delimiters() {
        QFETCH(QString, text);
        QFETCH(char, delimiter);
        CsvTable t;
        CsvError e;
        QVERIFY2(parseCsvTable(text.toStdString(), "mem", t, e), e.what().c_str());
        QCOMPARE(t.delimiter, delimiter);
        QCOMPARE(t.header.size(), size_t(2));
        QCOMPARE(t.header[0], std::string("t"));
        QCOMPARE(t.header[1], std::string("x"));
        QCOMPARE(t.column("x"), 1);
        QCOMPARE(t.column("nope"), -1);
        QCOMPARE(t.rows(), size_t(2));
        QCOMPARE(t.columns[1][0], 1.5);
        QCOMPARE(t.columns[1][1], -2e-3);
        QCOMPARE(t.columns[0][1], 1.0);
    }

    void commentsAndBlankLinesSkipped() {
        const std::string text = "# source: test\n  # second comment\n\ntime_s,f\n# inline comment\n0,1\n\n2,3\n";
        CsvTable t;
        CsvError e;
        QVERIFY2(parseCsvTable(text, "mem", t, e), e.what().c_str());
        QCOMPARE(t.comments.size(), size_t(3));
        QCOMPARE(t.comments[0], std::string("source: test"));
        QCOMPARE(t.comments[2], std::string("inline comment"));
        QCOMPARE(t.headerLine, 4L);
        QCOMPARE(t.rows(), size_t(2));
        QCOMPARE(t.rowLines[0], 6L);
        QCOMPARE(t.rowLines[1], 8L);
        QCOMPARE(t.columns[1][1], 3.0);
    }

    void badCellHasLineAndColumn_data() {
        QTest::addColumn<QString>("text");
        QTest::addColumn<long>("line");
        QTest::addColumn<long>("column");
        QTest::newRow("letters") << "# c\na,bb,c\n1,2,3\n4,x5,6\n" << 4L << 3L;
        QTest::newRow("empty cell") << "a,bb,c\n1,,3\n" << 2L << 3L;
        QTest::newRow("nan") << "a;b\n1;2\n3;nan\n" << 3L << 3L;
        QTest::newRow("inf") << "a,b\ninf,2\n" << 2L << 1L;
        QTest::newRow("trailing junk") << "a,b\n1,2.5.1\n" << 2L << 3L;
        QTest::newRow("tab third") << "a\tb\tc\n10\t20\t3o\n" << 2L << 7L;
        QTest::newRow("bad quote") << "a,b\n1,\"2\n" << 2L << 5L;
    }
    void badCellHasLineAndColumn() {
        QFETCH(QString, text);
        QFETCH(long, line);
        QFETCH(long, column);
        CsvTable t;
        t.header = {"untouched"};
        CsvError e;
        QVERIFY(!parseCsvTable(text.toStdString(), "in.csv", t, e));
        QCOMPARE(e.file, std::string("in.csv"));
        QCOMPARE(e.line, line);
        QCOMPARE(e.column, column);
        const std::string prefix = "in.csv:" + std::to_string(line) + ":" + std::to_string(column) + ": ";
        QVERIFY2(e.what().rfind(prefix, 0) == 0, e.what().c_str());
        // Nothing half-loaded: the output table is exactly as it was.
        QCOMPARE(t.header.size(), size_t(1));
        QCOMPARE(t.header[0], std::string("untouched"));
        QVERIFY(t.columns.empty());
    }

    void raggedRow() {
        CsvTable t;
        CsvError e;
        QVERIFY(!parseCsvTable("a,b,c\n1,2,3\n4,5\n", "r.csv", t, e));
        QCOMPARE(e.line, 3L);
        QVERIFY2(e.message.find("expected 3") != std::string::npos, e.message.c_str());
        QVERIFY(!parseCsvTable("a,b\n1,2\n4,5,6\n", "r.csv", t, e));
        QCOMPARE(e.line, 3L);
        QCOMPARE(e.column, 5L);  // where the surplus field starts
        QVERIFY(t.header.empty());
    }

    void headerProblems() {
        CsvTable t;
        CsvError e;
        QVERIFY(!parseCsvTable("# only comments\n\n", "h.csv", t, e));
        QVERIFY(!parseCsvTable("", "h.csv", t, e));
        QVERIFY(!parseCsvTable("a,,c\n1,2,3\n", "h.csv", t, e));
        QCOMPARE(e.line, 1L);
        QCOMPARE(e.column, 3L);
        QVERIFY(!parseCsvTable("a,b,a\n1,2,3\n", "h.csv", t, e));
        QVERIFY2(e.message.find("duplicate") != std::string::npos, e.message.c_str());
        // A header without data is a valid, empty table.
        QVERIFY(parseCsvTable("a,b\n", "h.csv", t, e));
        QCOMPARE(t.rows(), size_t(0));
        QCOMPARE(t.columns.size(), size_t(2));
    }

    void missingFile() {
        CsvTable t;
        CsvError e;
        QVERIFY(!readCsvTable("/nonexistent/dir/file.csv", t, e));
        QCOMPARE(e.file, std::string("/nonexistent/dir/file.csv"));
        QVERIFY2(e.what().find("/nonexistent/dir/file.csv") != std::string::npos, e.what().c_str());
        QVERIFY(e.message.find("cannot open") != std::string::npos);
    }

    void readsSharedRealData() {
        const std::string path = std::string(STICKSLIP_SHARED_DIR) + "/data/real/friction-damper/1Hz_30lb_1in.csv";
        if (!std::filesystem::exists(path)) QSKIP("shared data not present");
        CsvTable t;
        CsvError e;
        QVERIFY2(readCsvTable(path, t, e), e.what().c_str());
        QCOMPARE(t.path, path);
        QCOMPARE(t.comments.size(), size_t(4));
        QVERIFY(t.column("time_s") == 0);
        QVERIFY(t.column("friction_force_N") >= 0);
        QVERIFY(t.rows() > 1000);
        // 1024 samples per second.
        QVERIFY(std::abs((t.columns[0][1] - t.columns[0][0]) - 1.0 / 1024.0) < 1e-6);
    }

    void atomicWriteReplacesAndLeavesNoTemp() {
        QTemporaryDir dir;
        QVERIFY(dir.isValid());
        const std::string path = dir.filePath("out.csv").toStdString();
        std::string err;
        QVERIFY2(writeFileAtomically(path, "first\n", &err), err.c_str());
        QCOMPARE(slurp(path), std::string("first\n"));
        QVERIFY2(writeFileAtomically(path, "second, longer content\n", &err), err.c_str());
        QCOMPARE(slurp(path), std::string("second, longer content\n"));
        size_t files = 0;
        for (const auto& entry : std::filesystem::directory_iterator(dir.path().toStdString())) {
            (void)entry;
            ++files;
        }
        QCOMPARE(files, size_t(1));  // no temporary left behind
        // Round trip through the reader.
        QVERIFY(writeFileAtomically(path, "a;b\n1;2\n", &err));
        CsvTable t;
        CsvError e;
        QVERIFY2(readCsvTable(path, t, e), e.what().c_str());
        QCOMPARE(t.columns[1][0], 2.0);
    }

    void atomicWriteFailureKeepsTarget() {
        std::string err;
        QVERIFY(!writeFileAtomically("/nonexistent/dir/out.csv", "x", &err));
        QVERIFY2(err.find("/nonexistent/dir/out.csv") != std::string::npos, err.c_str());
        QVERIFY(!writeFileAtomically("", "x", &err));
    }
};

QTEST_GUILESS_MAIN(TstCsvTable)
#include "tst_csv_table.moc"
