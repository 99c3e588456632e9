#include "command_line.hpp"

#include <QByteArray>

namespace stickslip::gui {

QString takeSessionArgument(int& argc, char** argv) {
    QString file;
    int out = 1;
    for (int i = 1; i < argc; ++i) {
        const QByteArray a(argv[i]);
        if ((a == "--session" || a == "-session") && i + 1 < argc) {
            file = QString::fromLocal8Bit(argv[++i]);
        } else if (a.startsWith("--session=")) {
            file = QString::fromLocal8Bit(a.mid(10));
        } else {
            argv[out++] = argv[i];
        }
    }
    argc = out;
    argv[argc] = nullptr;
    return file;
}


}  // namespace stickslip::gui
