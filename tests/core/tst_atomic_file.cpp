// io::AtomicFileWriter: the target changes only on commit(), whole; an abandoned or failed
// writer leaves the target byte for byte and no temporary; the target's mode is kept.
#include <QDir>
#include <QFile>
#include <QTemporaryDir>
#include <QtTest>

#include <sys/stat.h>

#include "core/io/atomic_file.hpp"
#include "core/io/csv_table.hpp"
#include "tests/file_bytes.hpp"

using stickslip::io::AtomicFileWriter;

namespace {

QStringList filesIn(const QString& dir) { return QDir(dir).entryList(QDir::Files); }

}  // namespace

class TstAtomicFile : public QObject {
    Q_OBJECT
    QTemporaryDir dir;
    std::string at(const char* name) const { return dir.filePath(name).toStdString(); }

private slots:
    void initTestCase() { QVERIFY(dir.isValid()); }

    void targetChangesOnlyOnCommit() {
        const std::string path = at("a.csv");
        QVERIFY(stickslip::io::writeFileAtomically(path, "old\n", nullptr));
        AtomicFileWriter w(path);
        QVERIFY(w.open());
        QVERIFY(w.write("new, "));
        QVERIFY(w.write("in two parts\n"));
        QCOMPARE(readAll(dir.filePath("a.csv")), QByteArray("old\n"));  // not yet
        QVERIFY(QFileInfo::exists(QString::fromStdString(w.tempPath())));
        QVERIFY2(w.commit(), w.error().c_str());
        QCOMPARE(readAll(dir.filePath("a.csv")), QByteArray("new, in two parts\n"));
        QCOMPARE(filesIn(dir.path()), QStringList{"a.csv"});
    }

    void abandonedWriterLeavesTargetAndNoTemporary() {
        const std::string path = at("b.csv");
        QVERIFY(stickslip::io::writeFileAtomically(path, "kept\n", nullptr));
        {
            AtomicFileWriter w(path);
            QVERIFY(w.open());
            QVERIFY(w.write("half a fi"));
        }  // no commit
        QCOMPARE(readAll(dir.filePath("b.csv")), QByteArray("kept\n"));
        AtomicFileWriter w(path);
        QVERIFY(w.open());
        QVERIFY(w.write("x"));
        w.abort();
        QVERIFY(!w.commit());
        QCOMPARE(readAll(dir.filePath("b.csv")), QByteArray("kept\n"));
        QVERIFY(!filesIn(dir.path()).join(' ').contains(".tmp."));
    }

    void modeOfTheTargetIsKept() {
        const std::string path = at("c.csv");
        QVERIFY(stickslip::io::writeFileAtomically(path, "1\n", nullptr));
        QVERIFY(::chmod(path.c_str(), 0600) == 0);
        QVERIFY(stickslip::io::writeFileAtomically(path, "2\n", nullptr));
        struct stat st {};
        QVERIFY(::stat(path.c_str(), &st) == 0);
        QCOMPARE(int(st.st_mode & 07777), 0600);
    }

    void errorsNameTheFile() {
        const std::string path = at("no/such/dir/d.csv");
        AtomicFileWriter w(path);
        QVERIFY(!w.open());
        QVERIFY2(w.error().rfind(path + ": cannot create temporary file", 0) == 0, w.error().c_str());
        QVERIFY(!w.write("x"));
        std::string why;
        QVERIFY(!stickslip::io::writeFileAtomically(path, "x", &why));
        QVERIFY2(why.rfind(path + ": ", 0) == 0, why.c_str());
        AtomicFileWriter empty("");
        QVERIFY(!empty.open());
        QVERIFY2(empty.error().find("empty file name") != std::string::npos, empty.error().c_str());
    }
};

QTEST_GUILESS_MAIN(TstAtomicFile)
#include "tst_atomic_file.moc"
