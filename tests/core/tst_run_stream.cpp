// Streamed run output: RunControl::onSample receives every output sample in place of
// RunResult::samples (dynamics, harmonic prescribed slip, a measured slip history), and
// io::RunCsvStream fed from it writes the same bytes as writeRunCsv of the whole run; an
// abandoned stream leaves no file at all.
#include <QDir>
#include <QFile>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>

#include "core/integrate/simulate.hpp"
#include "core/io/run_csv.hpp"
#include "core/presets.hpp"

#include "tests/file_bytes.hpp"

using namespace stickslip;
using namespace stickslip::io;

namespace {

SimParams fig20(SetupKind setup) {
    Preset pr;
    findPreset("fig20", pr);
    SimParams p = pr.params;
    p.setup = setup;
    p.cycles = 3;
    p.transientCycles = 1;
    return p;
}

}  // namespace

class TstRunStream : public QObject {
    Q_OBJECT
    QTemporaryDir dir;

    // The whole run's file and the streamed one, byte for byte.
    void compareStreamed(const SimParams& p, const SlipHistory* history, const char* name) {
        const RunResult whole = simulate(p, RunControl{}, history);
        QVERIFY2(whole.ok(), whole.message.c_str());
        QVERIFY(whole.samples.size() > 100);
        const std::string path = dir.filePath(name).toStdString();
        RunCsvStream stream(path);
        std::string error;
        QVERIFY2(stream.open(&error), error.c_str());
        RunControl ctl;
        size_t seen = 0;
        ctl.onSample = [&](const Sample& x) {
            stream.add(x);
            ++seen;
        };
        const RunResult streamed = simulate(p, ctl, history);
        QVERIFY(streamed.ok());
        QCOMPARE(streamed.samples.size(), size_t(0));  // nothing kept in memory
        QCOMPARE(seen, whole.samples.size());
        QVERIFY2(stream.finish(p, streamed, &error, {"input = x"}), error.c_str());
        QCOMPARE(readAll(QString::fromStdString(path)), QByteArray::fromStdString(runCsvText(p, whole, {"input = x"})));
    }

private slots:
    void initTestCase() { QVERIFY(dir.isValid()); }

    void dynamicsStreamsTheSameFile() { compareStreamed(fig20(SetupKind::Dynamics), nullptr, "dyn.csv"); }

    void prescribedStreamsTheSameFile() { compareStreamed(fig20(SetupKind::Prescribed), nullptr, "pre.csv"); }

    void measuredHistoryStreamsTheSameFile() {
        std::vector<double> t, g;
        for (int i = 0; i <= 2000; ++i) {
            t.push_back(i * 1e-3);
            g.push_back(2e-3 * std::sin(2 * M_PI * 3.0 * t.back()));
        }
        const SlipHistory h = SlipHistory::fromSlip(t, g);
        compareStreamed(fig20(SetupKind::Prescribed), &h, "hist.csv");
    }

    void abandonedStreamLeavesNoFile() {
        QTemporaryDir empty;
        {
            RunCsvStream stream(empty.filePath("gone.csv").toStdString());
            std::string error;
            QVERIFY2(stream.open(&error), error.c_str());
            Sample x;
            for (int i = 0; i < 20000; ++i) stream.add(x);  // more than one block
        }
        QCOMPARE(QDir(empty.path()).entryList(QDir::Files | QDir::Hidden), QStringList());
    }

    void unwritableDirectoryIsAnError() {
        RunCsvStream stream(dir.filePath("no/such/dir/x.csv").toStdString());
        std::string error;
        QVERIFY(!stream.open(&error));
        QVERIFY2(error.find("no/such/dir/x.csv: cannot create temporary file") != std::string::npos, error.c_str());
    }
};

QTEST_GUILESS_MAIN(TstRunStream)
#include "tst_run_stream.moc"
