// The bytes of a file, for tests that compare outputs byte for byte (empty if it cannot be read),
// and the comparison of an exported plot with one of its versions.
#pragma once

#include <QByteArray>
#include <QFile>
#include <QString>

inline QByteArray readAll(const QString& path) {
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

// Whether `now` is the export `version` of a plot in format `kind` (session, png, svg, pdf, csv):
// byte for byte, except a PDF, which carries its creation time, so that two writes of one plot
// differ in a few bytes of equal length: a PDF is that version when it is whole (header, %%EOF
// trailer) and has that version's size.
inline bool sameExportVersion(const QString& kind, const QByteArray& now, const QByteArray& version) {
    if (kind != "pdf") return now == version;
    return now.size() == version.size() && now.startsWith("%PDF-") && now.trimmed().endsWith("%%EOF");
}
