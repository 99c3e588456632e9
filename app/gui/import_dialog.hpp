// Importing measured runs (issue 5): data files, a column mapping with units (one combo per
// signal, defaulting to the core's column names), an optional manifest, per-run settings
// (the CLI's --run-set), the set-up, and the cleaning settings with a raw-versus-cleaned
// plot of one signal of the selected run. Problems (unreadable or malformed file, missing
// column, bad unit, manifest, settings) are shown in words with file:line:column and keep
// OK disabled. The dataset is loaded on OK, off the GUI thread; a failure keeps the dialog
// open with the error and nothing half-loaded.
#pragma once

#include <QDialog>
#include <QFutureWatcher>
#include <QStringList>
#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/identify/preprocess.hpp"
#include "core/io/csv_table.hpp"
#include "core/io/dataset.hpp"
#include "core/params.hpp"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QListWidget;
class QPlainTextEdit;
class QPushButton;
class QSpinBox;
class QTableWidget;
class QTimer;

namespace stickslip::widgets {
class SignalComparePlot;
}

namespace stickslip::gui {

// What the dialog knows about one data file without loading it: header, the first rows for
// the preview, or the error that stops it from loading (read off the GUI thread).
struct FilePreview {
    QString path;
    bool ok = false;
    io::CsvError error;                       // when !ok
    std::vector<std::string> header;
    std::vector<std::vector<double>> rows;    // first rows, row-major
    std::vector<long> rowLines;               // source line of each preview row
    std::vector<std::string> comments;
    long headerLine = 0;
    size_t rowCount = 0;
    // Per column: median step (> 0 only if the column increases) and the first data row
    // i >= 1 where it does not increase (0 if none) with the two values, to check a time column.
    std::vector<double> medianStep;
    std::vector<size_t> firstNonIncreasing;
    std::vector<long> firstNonIncreasingLine;
    std::vector<std::pair<double, double>> nonIncreasingValues;
};
// Reads `path` with the core CSV reader and keeps the first `maxRows` rows.
FilePreview readFilePreview(const QString& path, int maxRows = 50);

// The raw and cleaned version of one run for the comparison plot.
struct CleaningPreview {
    quint64 generation = 0;
    QString file;
    bool ok = false;
    QString error;       // loading or cleaning failed (in words, file:line:column when known)
    io::Run raw;         // loaded with the dialog's mapping and settings
    identify::CleanRun clean;
};
// Loads `file` alone with `options` (run-sets that name other files are ignored) and cleans it.
CleaningPreview computeCleaningPreview(const QString& file, const io::DatasetOptions& options,
                                       const identify::PreprocessSettings& settings);

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

    QComboBox* columnCombo(io::Signal s) const { return columnCombos_[static_cast<size_t>(s)]; }
    QComboBox* unitCombo(io::Signal s) const { return unitCombos_[static_cast<size_t>(s)]; }
    QTableWidget* previewTable() const { return preview_; }
    widgets::SignalComparePlot* comparePlot() const { return plot_; }
    QPushButton* okButton() const { return okButton_; }
    QLabel* messageLabel() const { return message_; }
    // The last finished cleaning preview (for the selected file).
    const CleaningPreview& cleaningPreview() const { return cleaning_; }

public slots:
    void accept() override;   // starts loading; closes only when it succeeds

signals:
    void previewsUpdated();   // file headers read
    void cleaningUpdated();   // the raw-vs-cleaned plot shows a new result
    void loadFailed(const QString& message);

private:
    void buildUi();
    QWidget* buildFilesPanel();
    QWidget* buildColumnsPage();
    QWidget* buildCleaningPage();
    void addFilesClicked();
    void removeFileClicked();
    void browseManifest();
    void scanFiles();
    void onScanFinished();
    void populateColumnCombos();
    void updatePreviewTable();
    void revalidate();
    void scheduleCleaning();
    void startCleaning();
    void onCleaningFinished();
    void showCleaning();
    void onLoadFinished();
    void settingsChanged();
    void columnChosen(io::Signal s);
    void updateEnabledStates();
    void updateSetupHint();
    QString validateFilesAndMapping() const;
    QString validateManifestAndRunSets();
    QString validateCleaning() const;
    QString summaryText() const;
    QStringList columnUnion() const;
    double timeScale() const;
    const FilePreview* selectedPreview() const;
    io::ColumnMapping mapping(QString* error) const;
    QStringList runSetLines() const;

    // files
    QListWidget* fileList_ = nullptr;
    QPushButton *addButton_ = nullptr, *removeButton_ = nullptr;
    QLineEdit* manifest_ = nullptr;
    QPlainTextEdit* runSets_ = nullptr;
    QComboBox* setup_ = nullptr;
    QLabel* setupHint_ = nullptr;
    // columns
    std::array<QComboBox*, io::kSignalCount> columnCombos_{};
    std::array<QComboBox*, io::kSignalCount> unitCombos_{};
    QTableWidget* preview_ = nullptr;
    QLabel* previewCaption_ = nullptr;
    // cleaning
    QCheckBox *bandStop_ = nullptr, *lowPass_ = nullptr, *steadyTrim_ = nullptr, *resample_ = nullptr;
    QDoubleSpinBox *bandCenter_ = nullptr, *bandWidth_ = nullptr, *lowPassHz_ = nullptr;
    QSpinBox *bandOrder_ = nullptr, *lowPassOrder_ = nullptr, *sgHalf_ = nullptr, *sgOrder_ = nullptr,
             *stageHarmonics_ = nullptr;
    QDoubleSpinBox *trimStart_ = nullptr, *trimEnd_ = nullptr, *trimFraction_ = nullptr;
    QComboBox* plotSignal_ = nullptr;
    QCheckBox* detail_ = nullptr;
    QLabel* cleaningStatus_ = nullptr;
    widgets::SignalComparePlot* plot_ = nullptr;
    // bottom
    QLabel* message_ = nullptr;
    QPushButton* okButton_ = nullptr;

    // state
    std::map<QString, FilePreview> previews_;   // by path
    QFutureWatcher<std::vector<FilePreview>> scanWatcher_;
    bool scanning_ = false;
    bool rescanPending_ = false;
    QTimer* cleaningTimer_ = nullptr;
    QFutureWatcher<CleaningPreview> cleaningWatcher_;
    quint64 cleaningGeneration_ = 0;
    bool cleaningRunning_ = false;
    bool cleaningPending_ = false;
    CleaningPreview cleaning_;
    struct LoadResult {
        bool ok = false;
        io::Dataset dataset;
        io::DatasetError error;
    };
    QFutureWatcher<LoadResult> loadWatcher_;
    bool loading_ = false;
    bool valid_ = false;
    QString error_;
    io::Dataset dataset_;
    bool populating_ = false;
    std::array<QString, io::kSignalCount> chosen_;   // null: default; "": none; else the column
    QString loadError_;
    // manifest read once per path
    QString manifestReadPath_;
    bool manifestOk_ = false;
    io::Manifest manifestData_;
    io::DatasetError manifestError_;
};

}  // namespace stickslip::gui
