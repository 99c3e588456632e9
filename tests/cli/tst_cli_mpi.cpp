// stickslip-cli under `mpirun -np 2 --oversubscribe` (registered only when CMake found MPI):
// map, sweep --mode independent and resumed checkpoints of both write byte for byte what one
// process writes; a bad option fails on every rank with one message.
#include <QFile>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>

#include "cli_runner.hpp"

using stickslip::testing::CliResult;
using stickslip::testing::runCli;
using stickslip::testing::runProcess;

#include "tests/file_bytes.hpp"

namespace {

CliResult runMpi(int ranks, const QStringList& cliArgs, int timeout_ms = 120000) {
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    // Tests may run as root (containers, CI); OpenMPI refuses that unless told.
    env.insert("OMPI_ALLOW_RUN_AS_ROOT", "1");
    env.insert("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1");
    env.insert("OMPI_MCA_rmaps_base_oversubscribe", "1");
    // Under scripts/sanitize.sh: OpenMPI keeps allocations from MPI_Init past MPI_Finalize, which
    // LeakSanitizer would report as leaks of ours; address and UB checks stay on. (The core and
    // checkpoint code are leak-checked by the tests that run without MPI.)
    if (env.contains("ASAN_OPTIONS")) env.insert("ASAN_OPTIONS", env.value("ASAN_OPTIONS") + ":detect_leaks=0");
    const QStringList args{"--oversubscribe", "-np", QString::number(ranks), QStringLiteral(STICKSLIP_CLI)};
    return runProcess(QStringLiteral(STICKSLIP_MPIEXEC), args + cliArgs, timeout_ms, env);
}

QStringList mapArgs(const QString& out) {
    return {"map",      "--preset", "fig20", "--from",   "0.2mm", "--to",    "5mm",  "--steps", "5", "--param2",
            "f",        "--from2",  "3",     "--to2",    "10",    "--steps2", "4",   "--settle", "20",
            "--samples", "32",      "--threads", "1",    "--out", out};
}

}  // namespace

class TstCliMpi : public QObject {
    Q_OBJECT
    QTemporaryDir dir;
    QString at(const char* name) const { return dir.filePath(name); }

private slots:
    void mapIsByteIdenticalOnTwoRanks() {
        const CliResult one = runCli(mapArgs(at("one.csv")));
        QVERIFY2(one.exitCode == 0, one.err.constData());
        const CliResult two = runMpi(2, mapArgs(at("two.csv")));
        QVERIFY2(two.exitCode == 0, two.err.constData());
        QVERIFY(readAll(at("one.csv")).contains("# status = ok"));
        QCOMPARE(readAll(at("two.csv")), readAll(at("one.csv")));
        // Three ranks on 20 cells: uneven shares still assemble to the same bytes.
        const CliResult three = runMpi(3, mapArgs(at("three.csv")));
        QVERIFY2(three.exitCode == 0, three.err.constData());
        QCOMPARE(readAll(at("three.csv")), readAll(at("one.csv")));
    }

    void independentSweepIsByteIdenticalOnTwoRanks() {
        const QStringList args{"sweep", "--preset", "fig20", "--from", "0.2mm", "--to", "3mm", "--steps", "7",
                               "--mode", "independent", "--direction", "both", "--settle", "20", "--samples", "24",
                               "--threads", "1"};
        const CliResult one = runCli(args + QStringList{"--out", at("s1.csv"), "--summary", at("s1s.csv")});
        QVERIFY2(one.exitCode == 0, one.err.constData());
        const CliResult two = runMpi(2, args + QStringList{"--out", at("s2.csv"), "--summary", at("s2s.csv")});
        QVERIFY2(two.exitCode == 0, two.err.constData());
        QVERIFY(readAll(at("s1s.csv")).contains("# status = ok"));
        QCOMPARE(readAll(at("s2.csv")), readAll(at("s1.csv")));
        QCOMPARE(readAll(at("s2s.csv")), readAll(at("s1s.csv")));
        // Logged by two ranks, cut mid-line, resumed by two ranks.
        const CliResult logged = runMpi(2, args + QStringList{"--out", at("s3.csv"), "--checkpoint", at("s.ckpt")});
        QVERIFY2(logged.exitCode == 0, logged.err.constData());
        const QByteArray log = readAll(at("s.ckpt"));
        QCOMPARE(int(log.count("\nvalue ")), 7);
        QFile f(at("s.ckpt"));
        QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
        f.write(log.left(log.size() / 2));
        f.close();
        const CliResult resumed = runMpi(2, args + QStringList{"--out", at("s4.csv"), "--summary", at("s4s.csv"),
                                                               "--checkpoint", at("s.ckpt")});
        QVERIFY2(resumed.exitCode == 0, resumed.err.constData());
        QCOMPARE(readAll(at("s4.csv")), readAll(at("s1.csv")));
        QCOMPARE(readAll(at("s4s.csv")), readAll(at("s1s.csv")));
    }

    void checkpointResumesAcrossRankCounts() {
        // Written by one process, cut to half (mid-line), finished by two ranks.
        const CliResult one = runCli(mapArgs(at("c1.csv")) << "--checkpoint" << at("c.ckpt"));
        QVERIFY2(one.exitCode == 0, one.err.constData());
        const QByteArray log = readAll(at("c.ckpt"));
        QFile f(at("c.ckpt"));
        QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
        f.write(log.left(log.size() / 2));
        f.close();
        const CliResult two = runMpi(2, mapArgs(at("c2.csv")) << "--checkpoint" << at("c.ckpt"));
        QVERIFY2(two.exitCode == 0, two.err.constData());
        QCOMPARE(readAll(at("c2.csv")), readAll(at("c1.csv")));
        QCOMPARE(int(readAll(at("c.ckpt")).count("\ncell ")), 20);
    }

    void badOptionFailsOnceOnEveryRank() {
        const CliResult r = runMpi(2, {"map", "--from", "1mm", "--to", "2mm", "--from2", "x", "--to2", "3", "--out",
                                       at("bad.csv")});
        QVERIFY(r.exitCode != 0);
        QCOMPARE(int(r.err.count("stickslip-cli map: f = x")), 1);
        QVERIFY(!QFile::exists(at("bad.csv")));
    }
};

QTEST_GUILESS_MAIN(TstCliMpi)
#include "tst_cli_mpi.moc"
