// stickslip-cli and interruption: a writer killed with SIGKILL in the middle of writing (held
// there by the STICKSLIP_TEST_STALL_WRITE hook of core/io/atomic_file.cpp, so the kill lands
// mid-write every time) leaves the previous file byte for byte and nothing under the final
// name; SIGINT (Ctrl-C) or SIGTERM during a long sweep, map, fit or identify ends the command
// with exit code 5 and no output file, and a map's --checkpoint log stays resumable.
// Latencies (signal -> exit) are figures for bench/bench_memory.cpp --cancel, not checked here.
#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QProcess>
#include <QTemporaryDir>
#include <QThread>
#include <QtTest>

#include <csignal>

#include "cli_runner.hpp"

#include "tests/file_bytes.hpp"

namespace {

QString damper(const char* name) { return QStringLiteral(STICKSLIP_SHARED_DIR "/data/real/friction-damper/") + name; }

void writeText(const QString& path, const QByteArray& text) {
    QFile f(path);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(text);
}

// Waits until the process's stderr contains `marker` (true) or it ends / time runs out.
bool waitForStderr(QProcess& p, const QByteArray& marker, QByteArray& err, int timeout_ms) {
    QElapsedTimer t;
    t.start();
    while (t.elapsed() < timeout_ms) {
        p.waitForReadyRead(100);
        err += p.readAllStandardError();
        if (err.contains(marker)) return true;
        if (p.state() == QProcess::NotRunning) return false;
    }
    return false;
}

// Waits until process `pid` has a handler of its own for `sig` (the SigCgt mask of
// /proc/<pid>/status): a signal sent earlier, while the process is still loading its libraries,
// would meet the default action and kill it, whatever the command does with the signal later.
bool waitForHandler(qint64 pid, int sig, int timeout_ms) {
    QElapsedTimer t;
    t.start();
    while (t.elapsed() < timeout_ms) {
        QFile status(QStringLiteral("/proc/%1/status").arg(pid));
        if (!status.open(QIODevice::ReadOnly)) return false;
        for (const QByteArray& line : status.readAll().split('\n')) {
            if (!line.startsWith("SigCgt:")) continue;
            bool ok = false;
            const qulonglong mask = line.mid(7).trimmed().toULongLong(&ok, 16);
            if (ok && (mask >> (sig - 1)) & 1u) return true;
        }
        QThread::msleep(10);
    }
    return false;
}

// Files in `dir` other than those named.
QStringList othersIn(const QString& dir, const QStringList& known) {
    QStringList extra;
    for (const QString& f : QDir(dir).entryList(QDir::Files))
        if (!known.contains(f)) extra << f;
    return extra;
}

}  // namespace

class TstCliCancel : public QObject {
    Q_OBJECT
    QTemporaryDir dir;
    QString at(const QString& name) const { return dir.filePath(name); }

    // Starts the CLI with `args` and the hook that holds its first atomic write half done.
    static void startStalled(QProcess& p, const QStringList& args) {
        QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
        env.insert("STICKSLIP_TEST_STALL_WRITE", "60");
        p.setProcessEnvironment(env);
        p.start(QStringLiteral(STICKSLIP_CLI), args);
    }

    // Starts `args` with the stall hook, kills it mid-write, checks the previous `target`.
    void killMidWrite(const QStringList& args, const QString& target) {
        const QByteArray previous = "# the previous file, complete\n1,2,3\n";
        writeText(target, previous);
        QProcess p;
        startStalled(p, args);
        QByteArray err;
        QVERIFY2(waitForStderr(p, "stalled mid-write of ", err, 600000), err.constData());
        const int at = err.indexOf("stalled mid-write of ") + int(qstrlen("stalled mid-write of "));
        const QString temp = QString::fromLocal8Bit(err.mid(at, err.indexOf('\n', at) - at));
        QVERIFY2(temp.startsWith(target + ".tmp."), qPrintable(temp));
        QVERIFY2(QFileInfo(temp).size() > 0, "the temporary holds part of the new file");
        ::kill(static_cast<pid_t>(p.processId()), SIGKILL);
        QVERIFY(p.waitForFinished(10000));
        QCOMPARE(p.exitStatus(), QProcess::CrashExit);
        QCOMPARE(readAll(target), previous);   // byte-identical, never the half-written text
        // What stays behind is the temporary alone, under its own name (see atomic_file.hpp).
        QVERIFY(QFileInfo::exists(temp));
        QVERIFY(QFile::remove(temp));
    }

    // Starts a long job, sends `sig` once it runs, expects exit 5 and no `outputs`.
    void cancelJob(const QStringList& args, const QStringList& outputs, const QByteArray& startedMarker,
                   int sig = SIGINT) {
        QProcess p;
        p.start(QStringLiteral(STICKSLIP_CLI), args);
        QByteArray err;
        QVERIFY2(waitForStderr(p, startedMarker, err, 600000), err.constData());
        QVERIFY2(waitForHandler(p.processId(), sig, 600000), "the command never installed its signal handler");
        QThread::msleep(300);
        QVERIFY2(p.state() == QProcess::Running, "the job ended before it could be cancelled: make it longer");
        ::kill(static_cast<pid_t>(p.processId()), sig);
        // Generous: the 1 s figure is measured by bench_memory --cancel, not here.
        QVERIFY2(p.waitForFinished(15000), "no exit within 15 s of the signal");
        err += p.readAllStandardError();
        QCOMPARE(p.exitStatus(), QProcess::NormalExit);
        QVERIFY2(p.exitCode() == 5, err.constData());
        QVERIFY2(err.contains("cancel"), err.constData());
        for (const QString& o : outputs) QVERIFY2(!QFileInfo::exists(o), qPrintable(o + " was written"));
    }

private slots:
    void initTestCase() { QVERIFY(dir.isValid()); }

    void killedSimulateLeavesPreviousCsv() {
        killMidWrite({"simulate", "--preset", "fig20", "--cycles", "40", "--out", at("run.csv")}, at("run.csv"));
        QCOMPARE(othersIn(dir.path(), {"run.csv"}), QStringList());
    }

    void killedFitLeavesPreviousReport() {
        killMidWrite({"fit", "--data", damper("1Hz_30lb_1in.csv"), "--setup", "prescribed", "--free", "mu", "--multistarts",
                      "1", "--max-iterations", "2", "--report", at("fit.json")},
                     at("fit.json"));
    }

    // A second Ctrl-C ends the process at once, even inside a write (held there by the hook):
    // exit 128 + SIGINT, the previous file intact, only the temporary left beside it.
    void secondSignalStopsAtOnce() {
        const QString target = at("twice.csv");
        const QByteArray previous = "# previous\n";
        writeText(target, previous);
        QProcess p;
        startStalled(p, {"simulate", "--preset", "fig20", "--cycles", "5", "--out", target});
        QByteArray err;
        QVERIFY2(waitForStderr(p, "stalled mid-write of ", err, 600000), err.constData());
        ::kill(static_cast<pid_t>(p.processId()), SIGINT);
        QVERIFY2(waitForStderr(p, "cancelling", err, 10000), err.constData());
        QVERIFY(p.state() == QProcess::Running);  // the first signal only asks
        ::kill(static_cast<pid_t>(p.processId()), SIGINT);
        QVERIFY2(p.waitForFinished(15000), "no exit within 15 s of the second signal");
        QCOMPARE(p.exitStatus(), QProcess::NormalExit);
        QCOMPARE(p.exitCode(), 128 + SIGINT);
        QCOMPARE(readAll(target), previous);
        const QStringList temps = QDir(dir.path()).entryList({"twice.csv.*"}, QDir::Files);
        QCOMPARE(temps.size(), 1);
        QVERIFY2(temps.front().startsWith("twice.csv.tmp."), qPrintable(temps.front()));
        QVERIFY(QFile::remove(dir.filePath(temps.front())));
    }

    void sweepCancelsOnSigint() {
        cancelJob({"sweep", "--preset", "fig20", "--from", "0.2mm", "--to", "5mm", "--steps", "400", "--progress",
                   "--out", at("sweep.csv"), "--summary", at("sweep_sum.csv")},
                  {at("sweep.csv"), at("sweep_sum.csv")}, "sweep:");
    }

    void independentSweepCancelsOnSigterm() {
        cancelJob({"sweep", "--preset", "fig20", "--independent", "--from", "0.2mm", "--to", "5mm", "--steps", "400",
                   "--progress", "--out", at("isweep.csv")},
                  {at("isweep.csv")}, "sweep:", SIGTERM);
    }

    void mapCancelsAndKeepsCheckpoint() {
        const QStringList args{"map", "--preset", "fig20", "--from", "0.2mm", "--to", "5mm", "--steps", "40", "--param2",
                               "f", "--from2", "3", "--to2", "10", "--steps2", "40", "--progress", "--checkpoint",
                               at("map.ckpt"), "--out", at("map.csv")};
        cancelJob(args, {at("map.csv")}, "map:");
        const QByteArray log = readAll(at("map.ckpt"));
        QVERIFY(log.startsWith("# stickslip-cli map checkpoint v1\n"));
        QVERIFY(log.endsWith("\n"));  // no half line: every logged cell is whole
    }

    void fitCancelsOnSigint() {
        cancelJob({"fit", "--data", damper("1Hz_30lb_1in.csv"), damper("1Hz_30lb_1.5in.csv"), damper("1Hz_30lb_0.5in.csv"),
                   "--setup", "prescribed", "--multistarts", "20", "--agreeing-starts", "0", "--max-iterations", "200",
                   "--report", at("fit_c.json"), "--residuals", at("fit_c.csv")},
                  {at("fit_c.json"), at("fit_c.csv")}, "\n");
    }

    void identifyCancelsOnSigint() {
        cancelJob({"identify", "--data", damper("1Hz_30lb_1in.csv"), damper("1Hz_30lb_1.5in.csv"),
                   damper("1Hz_30lb_0.5in.csv"), "--setup", "prescribed", "--report", at("id.json"), "--html",
                   at("id.html")},
                  {at("id.json"), at("id.html")}, "identify:");
    }

    void reproduceCancelsOnSigint() {
        cancelJob({"reproduce", "--figure", "20", "--steps", "300", "--out", at("fig")}, {at("fig/fig20_sweep.csv")},
                  "sweep A");
        QCOMPARE(QDir(at("fig")).entryList(QDir::Files), QStringList());
    }

    void simulateCancelsOnSigint() {
        cancelJob({"simulate", "--preset", "fig20", "--cycles", "100000", "--out", at("long.csv")}, {at("long.csv")}, "",
                  SIGINT);
    }
};

QTEST_GUILESS_MAIN(TstCliCancel)
#include "tst_cli_cancel.moc"
