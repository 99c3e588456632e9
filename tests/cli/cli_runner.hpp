// Runs the built stickslip-cli (path STICKSLIP_CLI, set by tests/CMakeLists.txt) as a separate
// process and collects its exit code and output, for the CLI tests.
#pragma once

#include <QByteArray>
#include <QProcess>
#include <QProcessEnvironment>
#include <QStringList>

namespace stickslip::testing {

struct CliResult {
    int exitCode = -1;  // -1 when it crashed or timed out
    QByteArray out, err;
};

// Runs `program args` (with `env` when given) and collects exit code and output.
inline CliResult runProcess(const QString& program, const QStringList& args, int timeout_ms = 120000,
                            const QProcessEnvironment& env = QProcessEnvironment()) {
    QProcess p;
    if (!env.isEmpty()) p.setProcessEnvironment(env);
    p.start(program, args);
    CliResult r;
    if (!p.waitForFinished(timeout_ms)) {
        p.kill();
        p.waitForFinished();
        r.err = "timed out";
        return r;
    }
    r.exitCode = p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1;
    r.out = p.readAllStandardOutput();
    r.err = p.readAllStandardError();
    return r;
}

inline CliResult runCli(const QStringList& args, int timeout_ms = 120000) {
    return runProcess(QStringLiteral(STICKSLIP_CLI), args, timeout_ms);
}

}  // namespace stickslip::testing
