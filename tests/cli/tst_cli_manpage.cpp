// The generated man page (stickslip-cli manpage) documents every subcommand and every option
// that the subcommand's own --help lists, and is valid roff that man(1) renders.
#include <QRegularExpression>
#include <QSet>
#include <QTemporaryDir>
#include <QtTest>

#include "cli_runner.hpp"

using stickslip::testing::runCli;

namespace {

// Long options ("--name") in a --help text.
QSet<QString> longOptions(const QString& text) {
    QSet<QString> names;
    static const QRegularExpression re(QStringLiteral("(?:^|[\\s,])(--[a-z0-9][a-z0-9-]*)"));
    for (auto it = re.globalMatch(text); it.hasNext();) names.insert(it.next().captured(1));
    names.remove(QStringLiteral("--help"));
    return names;
}

}  // namespace

class TstCliManPage : public QObject {
    Q_OBJECT
private slots:
    void everyCommandAndOptionIsDocumented() {
        const auto man = runCli({"manpage"});
        QCOMPARE(man.exitCode, 0);
        // roff escapes '-' as '\-'; undo that to compare with --help.
        const QString page = QString::fromUtf8(man.out).replace(QStringLiteral("\\-"), QStringLiteral("-"));
        QVERIFY(page.startsWith(QStringLiteral(".\\\"")));
        QVERIFY(page.contains(QStringLiteral(".TH STICKSLIP-CLI 1")));
        QVERIFY2(!page.contains(QStringLiteral(".SS manpage")), "the hidden command must not document itself");
        const QStringList commands = {"simulate", "presets", "sweep", "map", "analyze", "reproduce", "fit", "identify"};
        for (const QString& c : commands) {
            const qsizetype at = page.indexOf(QStringLiteral(".SS ") + c + "\n");
            QVERIFY2(at >= 0, qPrintable("no section for " + c));
            qsizetype end = page.indexOf(QStringLiteral(".SS "), at + 4);
            if (end < 0) end = page.indexOf(QStringLiteral(".SH EXIT STATUS"));
            const QString section = page.mid(at, end - at);
            const auto help = runCli({c, "--help"});
            QCOMPARE(help.exitCode, 0);
            const QSet<QString> options = longOptions(QString::fromUtf8(help.out));
            for (const QString& o : options)
                QVERIFY2(section.contains(QStringLiteral(".B ") + o) || section.contains("," + o),
                         qPrintable(c + ": " + o + " is in --help but not in the man page"));
        }
    }

    // A two-way flag (--x,!--no-x) shows which of its two names is the default, in --help and in
    // the man page: CLI11 prints only the negation's value ("--no-x{false}"), which read as if the
    // default were off for flags that are on by default.
    void twoWayFlagsShowTheirDefault() {
        const auto help = runCli({"identify", "--help"});
        QCOMPARE(help.exitCode, 0);
        const QString text = QString::fromUtf8(help.out);
        const QStringList on = {"--held-out-restart", "--exact-state-step", "--null-numerics", "--curve-coordinates"};
        for (const QString& f : on) QVERIFY2(text.contains("=" + f + "\n"), qPrintable(f + " is on by default"));
        QVERIFY(text.contains(QStringLiteral("=--no-mask-edge-guard\n")));
        const auto man = runCli({"manpage"});
        QVERIFY(QString::fromUtf8(man.out).contains(QStringLiteral("(default: \\-\\-held\\-out\\-restart)")));
    }

    void writesAtomicallyToAFileAndManRendersIt() {
        QTemporaryDir dir;
        const QString file = dir.filePath(QStringLiteral("stickslip-cli.1"));
        QCOMPARE(runCli({"manpage", "--out", file}).exitCode, 0);
        QVERIFY(QFileInfo(file).size() > 1000);
        if (QStandardPaths::findExecutable(QStringLiteral("man")).isEmpty()) QSKIP("man(1) is not installed");
        QProcess man;
        man.setProcessEnvironment([] {
            auto env = QProcessEnvironment::systemEnvironment();
            env.insert(QStringLiteral("MANWIDTH"), QStringLiteral("100"));
            return env;
        }());
        man.start(QStringLiteral("man"), {QStringLiteral("-l"), file});
        QVERIFY(man.waitForFinished(30000));
        QCOMPARE(man.exitCode(), 0);
        const QString text = QString::fromUtf8(man.readAllStandardOutput());
        QVERIFY2(text.contains(QStringLiteral("EXIT STATUS")), qPrintable(text.left(400)));
        QVERIFY(text.contains(QStringLiteral("--steps-per-period")));
        QVERIFY2(!man.readAllStandardError().contains("warning"), "roff warnings");
    }
};

QTEST_GUILESS_MAIN(TstCliManPage)
#include "tst_cli_manpage.moc"
