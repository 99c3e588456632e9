// stickslip-cli map / sweep --mode independent --checkpoint, run as a separate process (no MPI
// needed): a run logs every cell; a run killed with SIGKILL part way, or a log cut mid-line,
// resumes to a CSV that is byte-identical to an uninterrupted run; a log from other settings,
// another command or a malformed one is refused with the file and line.
#include <QElapsedTimer>
#include <QFile>
#include <QProcess>
#include <QTemporaryDir>
#include <QThread>
#include <QtTest>

#include "cli_runner.hpp"

using stickslip::testing::CliResult;
using stickslip::testing::runCli;

#include "tests/file_bytes.hpp"

namespace {

// 6 × 5 cells, each about as costly as a default map cell (settle 50, samples 64).
QStringList mapArgs(const QString& out) {
    return {"map",       "--preset", "fig20", "--from",  "0.2mm", "--to",      "5mm", "--steps", "6",
            "--param2",  "f",        "--from2", "3",     "--to2",  "10",       "--steps2", "5", "--out",
            out};
}

int cellLines(const QByteArray& log) { return int(log.count("\ncell ")); }

}  // namespace

class TstCliCheckpoint : public QObject {
    Q_OBJECT
    QTemporaryDir dir;
    QByteArray reference;
    QString at(const char* name) const { return dir.filePath(name); }

private slots:
    void initTestCase() {
        QVERIFY(dir.isValid());
        const CliResult r = runCli(mapArgs(at("ref.csv")));
        QVERIFY2(r.exitCode == 0, r.err.constData());
        reference = readAll(at("ref.csv"));
        QVERIFY(reference.contains("# status = ok"));
    }

    void fullRunLogsEveryCell() {
        const CliResult r = runCli(mapArgs(at("a.csv")) << "--checkpoint" << at("a.ckpt"));
        QVERIFY2(r.exitCode == 0, r.err.constData());
        QCOMPARE(readAll(at("a.csv")), reference);
        const QByteArray log = readAll(at("a.ckpt"));
        QVERIFY(log.startsWith("# stickslip-cli map checkpoint v1\n# fingerprint "));
        QCOMPARE(cellLines(log), 30);
        // Resuming a complete log computes nothing and writes the same CSV.
        const CliResult again = runCli(mapArgs(at("b.csv")) << "--checkpoint" << at("a.ckpt"));
        QVERIFY2(again.exitCode == 0, again.err.constData());
        QCOMPARE(readAll(at("b.csv")), reference);
        QCOMPARE(readAll(at("a.ckpt")), log);
    }

    void tornLogResumesByteIdentical() {
        const QByteArray log = readAll(at("a.ckpt"));
        // Keep the header and about a third of the cells, the last one cut mid-line.
        const int cut = log.indexOf('\n', log.size() / 3) - 5;
        QFile f(at("torn.ckpt"));
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(log.left(cut));
        f.close();
        const CliResult r = runCli(mapArgs(at("torn.csv")) << "--checkpoint" << at("torn.ckpt") << "--threads" << "2");
        QVERIFY2(r.exitCode == 0, r.err.constData());
        QCOMPARE(readAll(at("torn.csv")), reference);
        const QByteArray resumed = readAll(at("torn.ckpt"));
        QCOMPARE(cellLines(resumed), 30);  // the torn line was cut, not kept half
        QVERIFY(resumed.endsWith('\n'));
    }

    void killedRunResumesByteIdentical() {
        QProcess p;
        p.start(QStringLiteral(STICKSLIP_CLI), mapArgs(at("k.csv")) << "--checkpoint" << at("k.ckpt") << "--threads"
                                                                   << "1");
        QVERIFY(p.waitForStarted());
        QElapsedTimer t;
        t.start();
        while (cellLines(readAll(at("k.ckpt"))) < 5 && t.elapsed() < 60000 && p.state() == QProcess::Running)
            QThread::msleep(10);
        p.kill();  // SIGKILL: no chance to tidy up
        p.waitForFinished();
        const int logged = cellLines(readAll(at("k.ckpt")));
        QVERIFY2(logged >= 5 && logged < 30, qPrintable(QString::number(logged)));
        QVERIFY(!QFile::exists(at("k.csv")));
        const CliResult r = runCli(mapArgs(at("k.csv")) << "--checkpoint" << at("k.ckpt"));
        QVERIFY2(r.exitCode == 0, r.err.constData());
        QCOMPARE(readAll(at("k.csv")), reference);
    }

    void foreignOrMalformedLogIsRefused() {
        const CliResult other = runCli(mapArgs(at("o.csv")) << "--settle" << "49" << "--checkpoint" << at("a.ckpt"));
        QCOMPARE(other.exitCode, 3);
        QVERIFY2(other.err.contains("a.ckpt:2: checkpoint was written for other settings"), other.err.constData());
        QVERIFY(!QFile::exists(at("o.csv")));
        QByteArray log = readAll(at("a.ckpt"));
        log.replace("\ncell 4 ", "\ncell 4 x ");
        QFile f(at("bad.ckpt"));
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(log);
        f.close();
        const CliResult bad = runCli(mapArgs(at("o.csv")) << "--checkpoint" << at("bad.ckpt"));
        QCOMPARE(bad.exitCode, 3);
        const int line = int(log.left(log.indexOf("\ncell 4 ")).count('\n')) + 2;  // cells are logged as they finish
        QVERIFY2(bad.err.contains(QString("bad.ckpt:%1: malformed checkpoint record").arg(line).toUtf8()),
                 bad.err.constData());
        QFile g(at("notmine.ckpt"));
        QVERIFY(g.open(QIODevice::WriteOnly));
        g.write("param_value,param2_value\n");
        g.close();
        const CliResult foreign = runCli(mapArgs(at("o.csv")) << "--checkpoint" << at("notmine.ckpt"));
        QCOMPARE(foreign.exitCode, 3);
        QVERIFY2(foreign.err.contains("notmine.ckpt:1: not a checkpoint of this command"), foreign.err.constData());
    }

    void independentSweepResumesByteIdentical() {
        const QStringList args{"sweep", "--preset", "fig20", "--from", "0.2mm", "--to", "3mm", "--steps", "9",
                               "--mode", "independent", "--direction", "both", "--settle", "20", "--samples", "24"};
        const CliResult ref = runCli(args + QStringList{"--out", at("s.csv"), "--summary", at("ss.csv")});
        QVERIFY2(ref.exitCode == 0, ref.err.constData());
        const CliResult full = runCli(args + QStringList{"--out", at("s1.csv"), "--summary", at("s1s.csv"),
                                                         "--checkpoint", at("s.ckpt")});
        QVERIFY2(full.exitCode == 0, full.err.constData());
        QCOMPARE(readAll(at("s1.csv")), readAll(at("s.csv")));
        QCOMPARE(readAll(at("s1s.csv")), readAll(at("ss.csv")));
        const QByteArray log = readAll(at("s.ckpt"));
        QVERIFY(log.startsWith("# stickslip-cli sweep checkpoint v1\n"));
        QCOMPARE(int(log.count("\nvalue ")), 9);
        QFile f(at("s.ckpt"));
        QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
        f.write(log.left(log.size() / 2));  // cuts a value's line in the middle
        f.close();
        const CliResult resumed = runCli(args + QStringList{"--out", at("s2.csv"), "--summary", at("s2s.csv"),
                                                            "--checkpoint", at("s.ckpt")});
        QVERIFY2(resumed.exitCode == 0, resumed.err.constData());
        QCOMPARE(readAll(at("s2.csv")), readAll(at("s.csv")));
        QCOMPARE(readAll(at("s2s.csv")), readAll(at("ss.csv")));
        QCOMPARE(int(readAll(at("s.ckpt")).count("\nvalue ")), 9);
        // A map's log is not a sweep's; a continuation cannot resume at all.
        const CliResult wrong = runCli(args + QStringList{"--out", at("s3.csv"), "--checkpoint", at("a.ckpt")});
        QCOMPARE(wrong.exitCode, 3);
        QVERIFY2(wrong.err.contains("a.ckpt:1: not a checkpoint of this command"), wrong.err.constData());
        const CliResult cont = runCli({"sweep", "--from", "1mm", "--to", "2mm", "--out", at("s4.csv"), "--checkpoint",
                                       at("c.ckpt")});
        QCOMPARE(cont.exitCode, 2);
        QVERIFY(cont.err.contains("--checkpoint needs --mode independent"));
        // --independent is short for --mode independent (and excludes --mode).
        QStringList shortArgs = args;
        shortArgs.removeAt(shortArgs.indexOf("--mode") + 1);
        shortArgs.replace(shortArgs.indexOf("--mode"), "--independent");
        const CliResult shorter = runCli(shortArgs + QStringList{"--out", at("s5.csv"), "--summary", at("s5s.csv")});
        QVERIFY2(shorter.exitCode == 0, shorter.err.constData());
        QCOMPARE(readAll(at("s5.csv")), readAll(at("s.csv")));
        QCOMPARE(runCli(args + QStringList{"--independent", "--out", at("s6.csv")}).exitCode, 2);
    }
};

QTEST_GUILESS_MAIN(TstCliCheckpoint)
#include "tst_cli_checkpoint.moc"
