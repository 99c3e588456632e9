// Importing measured runs (issue 5): data files, a column mapping with units (one combo per
// signal, defaulting to the core's column names), an optional manifest, per-run settings
// (the CLI's --run-set), the set-up, and the cleaning settings with a raw-versus-cleaned
// plot of one signal of the selected run. Problems (unreadable or malformed file, missing
// column, bad unit, manifest, settings) are shown in words with file:line:column and keep
// OK disabled. The dataset is loaded on OK, off the GUI thread; a failure keeps the dialog
// open with the error and nothing half-loaded.
//
// The dialog wires three pages (files, columns and units, cleaning; each owns its widgets and
// background job) and the Qt-free checks of import_validation.hpp; it loads on OK.
#pragma once

#include <QDialog>
#include <QFutureWatcher>
#include <QStringList>
#include <vector>

#include "cleaning_preview.hpp"
#include "core/identify/preprocess.hpp"
#include "core/io/dataset.hpp"
#include "core/params.hpp"
#include "file_preview.hpp"
#include "import_validation.hpp"

class QComboBox;
class QLabel;
class QPushButton;
class QTableWidget;

namespace stickslip::widgets {
class SignalComparePlot;
}

namespace stickslip::gui {

class ImportCleaningPage;
class ImportColumnsPage;
class ImportFilesPage;

class ImportDialog : public QDialog {
    Q_OBJECT
public:
    explicit ImportDialog(const QStringList& files, QWidget* parent = nullptr);
    ~ImportDialog() override;

    // --- the result, for the rest of the app -----------------------------------------
    // Mapping (columns differing from the core's default names; "(none)" as io::kNotMapped),
    // units (only non-SI),
    // manifest and run-sets, exactly as the CLI's --columns/--units/--manifest/--run-set.
    io::DatasetOptions datasetOptions() const;
    identify::PreprocessSettings preprocessSettings() const;
    // The chosen set-up; "automatic" resolves as the CLI does: dynamics when the first file
    // has a slider displacement column (after mapping), else prescribed.
    SetupKind setup() const;
    QStringList files() const;
    // The dataset loaded with datasetOptions() when OK succeeded (empty before); signals set
    // to "(none)" are not read.
    const io::Dataset& dataset() const { return dataset_; }

    // --- state and controls (tests, integration) ----------------------------------------
    bool isValid() const { return valid_; }          // OK enabled
    QString errorText() const;                       // the current problem, empty if none
    bool isBusy() const;                             // reading files, cleaning or loading
    // Signals the user set to "(none)" although the files carry the default column.
    std::vector<io::Signal> unmappedSignals() const;

    void setFiles(const QStringList& files);
    void setColumn(io::Signal s, const QString& column);   // "" or "(none)": not mapped
    QString column(io::Signal s) const;                     // "" when not mapped
    void setUnit(io::Signal s, const QString& unit);        // e.g. "mm", "lbf"
    QString unit(io::Signal s) const;
    void setManifestPath(const QString& path);
    void setRunSets(const QStringList& specs);              // "FILE:KEY=VALUE"
    void setSetupChoice(int index);                         // 0 automatic, 1 prescribed, 2 dynamics
    void setPreprocessSettings(const identify::PreprocessSettings& s);
    void setSelectedFile(int row);
    void setPlotSignal(io::Signal s);

    QComboBox* columnCombo(io::Signal s) const;
    QComboBox* unitCombo(io::Signal s) const;
    QTableWidget* previewTable() const;
    widgets::SignalComparePlot* comparePlot() const;
    QPushButton* okButton() const { return okButton_; }
    QLabel* messageLabel() const { return message_; }
    // The last finished cleaning preview (for the selected file).
    const CleaningPreview& cleaningPreview() const;

public slots:
    void accept() override;   // starts loading; closes only when it succeeds

signals:
    void previewsUpdated();   // file headers read
    void cleaningUpdated();   // the raw-vs-cleaned plot shows a new result
    void loadFailed(const QString& message);

private:
    void buildUi();
    void connectPages();
    void offerManifestNextTo(const QStringList& files);
    void onScanFinished();
    void updatePreviewTable();
    void revalidate();
    void showMessage(const QString& err, bool scanning);
    void onLoadFinished();
    void settingsChanged();
    void updateSetupHint();
    QString validationError();
    QString summaryText() const;
    QStringList columnUnion() const;

    ImportFilesPage* filesPage_ = nullptr;
    ImportColumnsPage* columnsPage_ = nullptr;
    ImportCleaningPage* cleaningPage_ = nullptr;
    QLabel* message_ = nullptr;
    QPushButton* okButton_ = nullptr;

    struct LoadResult {
        bool ok = false;
        io::Dataset dataset;
        io::DatasetError error;
    };
    QFutureWatcher<LoadResult> loadWatcher_;
    bool loading_ = false;
    bool valid_ = false;
    QString error_;
    QString loadError_;
    io::Dataset dataset_;
    ManifestCheck manifestCheck_;
};

}  // namespace stickslip::gui
