// A session: the parameters (every SimParams key, in SI), the model and set-up choice, the
// preset name, the measured file and which views are shown, as JSON (QJsonDocument),
// written atomically (QSaveFile).
#pragma once

#include <QByteArray>
#include <QString>
#include <QStringList>

#include "model_settings.hpp"

namespace stickslip::gui {

struct Session {
    ModelSettings settings;
    QStringList visibleViews;   // view ids (ViewSet::View::id)
    QString measuredFile;       // "" if none
    QByteArray windowState;     // QMainWindow::saveState(), may be empty

    QByteArray toJson() const;
    // false with a message (what is wrong, where) for malformed JSON or bad values;
    // parameters are validated as the panel does not accept NaN or unknown keys.
    static bool fromJson(const QByteArray& json, Session& out, QString* error);
};

// Atomic write (QSaveFile) / read; messages name the file.
bool saveSession(const Session& s, const QString& path, QString* error);
bool loadSession(const QString& path, Session& out, QString* error);

}  // namespace stickslip::gui
