// The import dialog's "Columns & units" page: one column combo and one unit combo per signal
// (defaulting to the core's column names) and a preview of the selected file with the signal
// each column feeds. The user's choices survive a rescan of the files.
#pragma once

#include <QStringList>
#include <QWidget>
#include <array>

#include "file_preview.hpp"
#include "import_signals.hpp"
#include "import_validation.hpp"

class QComboBox;
class QLabel;
class QTableWidget;

namespace stickslip::gui {

class ImportColumnsPage : public QWidget {
    Q_OBJECT
public:
    explicit ImportColumnsPage(QWidget* parent = nullptr);

    // Offers these columns (the union over the files) and picks the user's choice, else the
    // default name when present, else "(none)"; no signals.
    void populate(const QStringList& fileColumns);
    void setColumn(io::Signal s, const QString& column);   // "" or "(none)": not mapped
    QString column(io::Signal s) const;                     // "" when not mapped
    void setUnit(io::Signal s, const QString& unit);
    QString unit(io::Signal s) const;                       // trimmed
    SignalTexts columns() const;
    SignalTexts units() const;
    // The selected file (null while it is read; `haveFiles` tells "no file" from "reading").
    void showPreview(const FilePreview* p, bool haveFiles);

    QComboBox* columnCombo(io::Signal s) const { return columnCombos_[idx(s)]; }
    QComboBox* unitCombo(io::Signal s) const { return unitCombos_[idx(s)]; }
    QTableWidget* previewTable() const { return preview_; }

signals:
    void columnChanged();   // the user picked a column
    void unitChanged();

private:
    QWidget* buildMappingBox();
    QWidget* buildPreviewBox();
    void columnChosen(io::Signal s);
    void fillPreviewHeader(const FilePreview& p);
    void fitHeaderWidths();

    std::array<QComboBox*, io::kSignalCount> columnCombos_{};
    std::array<QComboBox*, io::kSignalCount> unitCombos_{};
    QTableWidget* preview_ = nullptr;
    QLabel* previewCaption_ = nullptr;
    bool populating_ = false;
    std::array<QString, io::kSignalCount> chosen_;   // null: default; "": none; else the column
};

}  // namespace stickslip::gui
