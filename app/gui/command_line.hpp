// Arguments the app must read before QApplication exists.
#pragma once

#include <QString>

namespace stickslip::gui {

// QGuiApplication consumes "-session ID" / "--session ID" (X11 session management), so the
// app's --session FILE never reached QCommandLineParser. This takes "--session FILE",
// "-session FILE" and "--session=FILE" out of argv (argc shrinks, argv[argc] = nullptr) before
// Qt sees them and returns FILE ("" if absent; the last one wins).
QString takeSessionArgument(int& argc, char** argv);

}  // namespace stickslip::gui
