#include "session.hpp"

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSaveFile>
#include <cmath>

#include "core/version.hpp"

namespace stickslip::gui {

namespace {
// Session format version written by this program. Readers accept every version up to this
// one (1: the first format; files without "program", "coulomb", "views" or "windowState", as
// hand-written or early sessions are, load with those left at their defaults; 2: adds
// "tolerance", the stepping of dynamics runs, 0 = fixed dt, which version 1 files load with)
// and refuse a newer one (naming it) rather than guessing at fields they do not know.
constexpr int kFormat = 2;
}

QByteArray Session::toJson() const {
    QJsonObject params;
    for (const auto& key : paramKeys()) {
        double v = 0.0;
        getParam(settings.params, key, v);
        params.insert(QString::fromStdString(key), v);
    }
    // The Coulomb law keeps its own μ and ε_T (setParam sets both laws at once).
    QJsonObject coulomb{{"mu", settings.params.lawParams<CoulombParams>().mu}, {"epsT", settings.params.lawParams<CoulombParams>().epsT_N_per_m}};
    QJsonObject root{
        {"format", "stickslip-session"},
        {"version", kFormat},
        {"program", QString::fromLatin1(kVersion)},
        {"model", toString(settings.model)},
        {"setup", QString::fromLatin1(stickslip::toString(settings.params.setup))},
        {"tolerance", settings.tolerance},
        {"preset", settings.preset},
        {"params", params},
        {"coulomb", coulomb},
        {"views", QJsonArray::fromStringList(visibleViews)},
        {"measuredFile", measuredFile},
        {"windowState", QString::fromLatin1(windowState.toBase64())},
    };
    return QJsonDocument(root).toJson(QJsonDocument::Indented);
}

bool Session::fromJson(const QByteArray& json, Session& out, QString* error) {
    auto fail = [&](const QString& m) {
        if (error) *error = m;
        return false;
    };
    QJsonParseError pe;
    const QJsonDocument doc = QJsonDocument::fromJson(json, &pe);
    if (pe.error != QJsonParseError::NoError) {
        // Line and column of the offset, counted in the text.
        const QByteArray head = json.left(pe.offset);
        const int line = head.count('\n') + 1;
        const int col = pe.offset - (head.lastIndexOf('\n') + 1) + 1;
        return fail(QStringLiteral("line %1, column %2: %3").arg(line).arg(col).arg(pe.errorString()));
    }
    const QJsonObject root = doc.object();
    if (root.value("format").toString() != "stickslip-session")
        return fail(QStringLiteral("not a StickSlip Lab session (\"format\" is not \"stickslip-session\")"));
    // A missing "version" is read as 1 (hand-written sessions often leave it out).
    const QJsonValue version = root.contains("version") ? root.value("version") : QJsonValue(1);
    if (!version.isDouble() || version.toDouble() != std::floor(version.toDouble()) || version.toDouble() < 1)
        return fail(QStringLiteral("\"version\" must be a whole number from 1 to %1").arg(kFormat));
    if (version.toDouble() > kFormat)
        return fail(QStringLiteral("session format version %1 was written by a newer StickSlip Lab%2; this version "
                                   "(%3) reads versions 1 to %4")
                        .arg(version.toDouble())
                        .arg(root.value("program").isString() ? " (" + root.value("program").toString() + ")"
                                                              : QString())
                        .arg(QString::fromLatin1(kVersion))
                        .arg(kFormat));
    Session s;
    if (!parseModelChoice(root.value("model").toString(), s.settings.model))
        return fail(QStringLiteral("unknown model \"%1\" (rate-state, coulomb or both)").arg(root.value("model").toString()));
    if (!parseSetupKind(root.value("setup").toString().toStdString(), s.settings.params.setup))
        return fail(QStringLiteral("unknown set-up \"%1\" (dynamics or prescribed)").arg(root.value("setup").toString()));
    s.settings.params.law = s.settings.primaryLaw();
    s.settings.preset = root.value("preset").toString();
    if (root.contains("tolerance")) {
        IntegrationParams ip;
        ip.tolerance = root.value("tolerance").toDouble(std::nan(""));
        const ParamIssues issues = ip.validate();  // the allowed range is IntegrationParams's own
        for (const ParamIssue& i : issues)
            if (i.field == "tolerance")  // a non-number reads as NaN, which is refused too
                return fail(QStringLiteral("\"tolerance\" must be %1").arg(QString::fromStdString(i.allowed)));
        s.settings.tolerance = ip.tolerance;
    } else {
        s.settings.tolerance = 0.0;  // version 1 had only the fixed step
    }
    const QJsonObject params = root.value("params").toObject();
    for (auto it = params.begin(); it != params.end(); ++it) {
        if (!it.value().isDouble() || !std::isfinite(it.value().toDouble()))
            return fail(QStringLiteral("params.%1: not a finite number").arg(it.key()));
        std::string why;
        if (!setParam(s.settings.params, it.key().toStdString(), it.value().toDouble(), &why))
            return fail(QStringLiteral("params.%1: %2").arg(it.key(), QString::fromStdString(why)));
    }
    const QJsonObject coulomb = root.value("coulomb").toObject();
    if (coulomb.contains("mu")) s.settings.params.lawParams<CoulombParams>().mu = coulomb.value("mu").toDouble();
    if (coulomb.contains("epsT")) s.settings.params.lawParams<CoulombParams>().epsT_N_per_m = coulomb.value("epsT").toDouble();
    for (const auto& v : root.value("views").toArray()) s.visibleViews << v.toString();
    s.measuredFile = root.value("measuredFile").toString();
    s.windowState = QByteArray::fromBase64(root.value("windowState").toString().toLatin1());
    out = s;
    return true;
}

bool saveSession(const Session& s, const QString& path, QString* error) {
    QSaveFile f(path);
    if (!f.open(QIODevice::WriteOnly)) {
        if (error) *error = QStringLiteral("%1: %2").arg(path, f.errorString());
        return false;
    }
    f.write(s.toJson());
    if (!f.commit()) {
        if (error) *error = QStringLiteral("%1: %2").arg(path, f.errorString());
        return false;
    }
    return true;
}

bool loadSession(const QString& path, Session& out, QString* error) {
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly)) {
        if (error) *error = QStringLiteral("%1: %2").arg(path, f.errorString());
        return false;
    }
    QString why;
    if (!Session::fromJson(f.readAll(), out, &why)) {
        if (error) *error = QStringLiteral("%1: %2").arg(path, why);
        return false;
    }
    return true;
}

}  // namespace stickslip::gui
